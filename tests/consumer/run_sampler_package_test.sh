#!/usr/bin/env bash
# The sampler package on a machine without the service's dependencies (a
# CTest): configures alignset from SOURCE_DIR without the service, with
# Protobuf, gRPC and SQLite made unfindable (CMAKE_DISABLE_FIND_PACKAGE_...),
# builds the sampler library and installs its component alone into a fresh
# prefix; then a consumer asks find_package(alignset COMPONENTS sampler) under
# the same ban (and pkg-config for alignset-sampler), builds, and renders
# through a lattice table that `alignset table` wrote, with no server.
#   run_sampler_package_test.sh ALIGNSET_CLI SOURCE_DIR
set -euo pipefail
CLI="$1"
SRC="$2"
WORK="$(mktemp -d /tmp/alignset-sampler-package-XXXXXX)"
trap 'rm -rf "$WORK"' EXIT
fail() { echo "run_sampler_package_test: $*" >&2; exit 1; }
NO_SERVICE=(-DCMAKE_DISABLE_FIND_PACKAGE_Protobuf=ON -DCMAKE_DISABLE_FIND_PACKAGE_gRPC=ON
            -DCMAKE_DISABLE_FIND_PACKAGE_SQLite3=ON)
GEN=()
command -v ninja >/dev/null && GEN=(-G Ninja)

cmake -S "$SRC" -B "$WORK/build" "${GEN[@]}" -DCMAKE_BUILD_TYPE=Release -DALIGNSET_BUILD_SERVICE=OFF \
  -DALIGNSET_BUILD_TESTS=OFF -DALIGNSET_BUILD_BENCH=OFF "${NO_SERVICE[@]}" > "$WORK/configure.log" 2>&1 \
  || { cat "$WORK/configure.log"; fail "configuring alignset without the service failed"; }
cmake --build "$WORK/build" --target alignset_sampler > "$WORK/build.log" 2>&1 \
  || { cat "$WORK/build.log"; fail "building the sampler library failed"; }
PREFIX="$WORK/prefix"
cmake --install "$WORK/build" --prefix "$PREFIX" --component sampler > "$WORK/install.log" 2>&1 \
  || { cat "$WORK/install.log"; fail "installing the sampler component failed"; }
for f in include/alignset/aligned_sampler.h include/alignset/set_table.h include/alignset/set_choice.h \
         include/alignset/pixel_shift.h include/alignset/lattice_points.h include/alignset/status.h; do
  [ -e "$PREFIX/$f" ] || fail "the sampler component lacks $f"
done
if [ -e "$PREFIX/include/alignset/client.h" ] || ls "$PREFIX"/lib/libalignset_client* >/dev/null 2>&1; then
  fail "the sampler component installed the client"
fi
if grep -n '#include "core/\|#include "client/\|#include "sampler/' "$PREFIX"/include/alignset/*.h; then
  fail "an installed header includes a repository path"
fi

# The consumer under the same ban: the package must not look for them.
cmake -S "$SRC/tests/consumer" -B "$WORK/consumer" "${GEN[@]}" -DCMAKE_BUILD_TYPE=Release \
  -DCONSUMER_SAMPLER_ONLY=ON -DCMAKE_PREFIX_PATH="$PREFIX" -DCMAKE_EXPORT_COMPILE_COMMANDS=ON "${NO_SERVICE[@]}" \
  > "$WORK/consumer-configure.log" 2>&1 || { cat "$WORK/consumer-configure.log"; fail "configuring the consumer failed"; }
cmake --build "$WORK/consumer" > "$WORK/consumer-build.log" 2>&1 \
  || { cat "$WORK/consumer-build.log"; fail "building the consumer failed"; }
if grep -q -e "$(realpath "$SRC")/sampler" -e "$(realpath "$SRC")/core" "$WORK/consumer/compile_commands.json"; then
  fail "the consumer compiled against the source tree, not the installed package"
fi
# pkg-config's sampler package too.
PC_DIR="$(dirname "$(find "$PREFIX" -name alignset-sampler.pc)")"
# shellcheck disable=SC2046
c++ -O1 -o "$WORK/pc-render" "$SRC/tests/consumer/render_with_table.cc" \
  $(PKG_CONFIG_PATH="$PC_DIR" pkg-config --cflags --libs alignset-sampler) \
  || fail "building the consumer with pkg-config (alignset-sampler) failed"

# A lattice table without a server, and both consumers' renders through it.
"$CLI" table -n 256 --construction lattice -o "$WORK/sets.tbl" > "$WORK/table.log" 2>&1 \
  || { cat "$WORK/table.log"; fail "alignset table failed"; }
"$WORK/consumer/render_with_table" "$WORK/sets.tbl" || fail "the CMake consumer's render failed"
"$WORK/pc-render" "$WORK/sets.tbl" || fail "the pkg-config consumer's render failed"
echo "run_sampler_package_test: the sampler package built, installed and rendered without gRPC, Protobuf or SQLite"

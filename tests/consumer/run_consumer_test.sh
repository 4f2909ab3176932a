#!/usr/bin/env bash
# The installed package, as a user meets it (a CTest): installs the build into a
# fresh prefix, builds tests/consumer against that prefix only, once with CMake's
# find_package(alignset) and once with pkg-config, starts the installed
# alignset-server on loopback and runs both consumers (and the installed Python
# package) against it.
#   run_consumer_test.sh BUILD_DIR SOURCE_DIR
set -euo pipefail
BUILD="$1"
SRC="$2"
WORK="$(mktemp -d /tmp/alignset-consumer-XXXXXX)"
. "$SRC/scripts/lib/loopback_server.sh"
cleanup() {
  stop_loopback_server
  rm -rf "$WORK"
}
trap cleanup EXIT
fail() { echo "run_consumer_test: $*" >&2; exit 1; }

PREFIX="$WORK/prefix"
cmake --install "$BUILD" --prefix "$PREFIX" > "$WORK/install.log" || { cat "$WORK/install.log"; fail "install failed"; }
for f in include/alignset/client.h include/alignset/status.h include/alignset/point_set.h \
         include/alignset/version.h include/alignset/set_table.h include/alignset/aligned_sampler.h include/alignset/prepass_fit.h \
         include/alignset/set_choice.h bin/alignset bin/alignset-server; do
  [ -e "$PREFIX/$f" ] || fail "the install lacks $f"
done
CONFIG="$(find "$PREFIX" -name alignsetConfig.cmake)"
PC="$(find "$PREFIX" -name alignset.pc)"
[ -n "$CONFIG" ] && [ -n "$PC" ] || fail "no alignsetConfig.cmake or alignset.pc"
# The installed headers stand alone: nothing includes a repository path.
if grep -n '#include "core/\|#include "client/' "$PREFIX"/include/alignset/*.h; then
  fail "an installed header includes a repository path"
fi

# 1. CMake: the consumer sees the prefix and nothing of the source or build tree.
GEN=()
command -v ninja >/dev/null && GEN=(-G Ninja)
cmake -S "$SRC/tests/consumer" -B "$WORK/cmake-build" "${GEN[@]}" -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_PREFIX_PATH="$PREFIX" -DCMAKE_EXPORT_COMPILE_COMMANDS=ON > "$WORK/configure.log" 2>&1 \
  || { cat "$WORK/configure.log"; fail "configuring the consumer failed"; }
cmake --build "$WORK/cmake-build" > "$WORK/build.log" 2>&1 || { cat "$WORK/build.log"; fail "building the consumer failed"; }
if grep -q -e "$(realpath "$BUILD")" -e "$(realpath "$SRC")/client" -e "$(realpath "$SRC")/core" \
     "$WORK/cmake-build/compile_commands.json"; then
  fail "the consumer compiled against the build or source tree, not the installed package"
fi

# 2. pkg-config.
PKG_CONFIG_PATH="$(dirname "$PC")" pkg-config --exists alignset || fail "pkg-config cannot find alignset"
# shellcheck disable=SC2046
c++ -O1 -o "$WORK/pc-consumer" "$SRC/tests/consumer/main.cc" \
  $(PKG_CONFIG_PATH="$(dirname "$PC")" pkg-config --cflags --libs alignset) \
  || fail "building the consumer with pkg-config failed"

# 3. The installed server on loopback, and both consumers against it.
start_loopback_server 30 "$WORK/server.log" "$PREFIX/bin/alignset-server" --db "$WORK/cache.sqlite" \
  --max-iterations 30 --workers 1 --threads-per-worker 1 --log-level warn \
  || fail "the installed server did not start"
"$WORK/cmake-build/alignset_consumer" "$ADDR"
"$WORK/pc-consumer" "$ADDR"

# 4. A renderer's path: precompute on the server, export a table with the
# installed CLI, render a scene of the consumer's own through the sampler
# library with that table alone (the consumer checks its edge pixels
# against Owen-Sobol at the same total samples).
"$PREFIX/bin/alignset" precompute --server "$ADDR" -n 256 --space 1dir --construction lattice > "$WORK/pre.log" 2>&1 \
  || { cat "$WORK/pre.log"; fail "precompute failed"; }
"$PREFIX/bin/alignset" export --db "$WORK/cache.sqlite" -n 256 --construction lattice -o "$WORK/sets.tbl" \
  > "$WORK/export.log" 2>&1 || { cat "$WORK/export.log"; fail "export failed"; }
"$WORK/cmake-build/render_with_table" "$WORK/sets.tbl" || fail "the consumer's render through the table failed"
# The installed Python package too, when the build made it.
PYDIR="$(find "$PREFIX" -type d -path '*dist-packages' | head -n 1)"
if [ -n "$PYDIR" ] && [ -f "$PYDIR/alignset/v1/alignset_pb2.py" ]; then
  PYTHONPATH="$PYDIR" /usr/bin/python3 -c "
import sys, alignset
p = alignset.Client(sys.argv[1], timeout=60).get(64, 30)
assert p.shape == (64, 2), p.shape
print('installed Python package: a (64, 2) set')" "$ADDR"
fi
echo "run_consumer_test: find_package and pkg-config consumers both fetched sets from $ADDR"

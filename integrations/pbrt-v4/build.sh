#!/usr/bin/env bash
# Builds pbrt-v4 with alignset's "aligned" sampler from a pbrt-v4 source folder,
# against Debian's packages and alignset's installed sampler library, with no
# network. The source folder is read, never written.
#
#   integrations/pbrt-v4/build.sh PBRT_SOURCE_DIR [OUT_DIR]
#
# OUT_DIR (default $BUILD_DIR/pbrt-v4, build/pbrt-v4) receives the alignset install it links
# (alignset/), the patched files and stand-ins (overlay/), pbrt's build
# (pbrt-build/) and the binary, OUT_DIR/bin/pbrt. A second run with the same
# source, patch and alignset does nothing and takes seconds (a stamp of their
# hashes); a changed file rebuilds what depends on it.
#
# Needs alignset built first (scripts/build.sh: the sampler library it
# installs from $BUILD_DIR) and the packages of `scripts/install-deps.sh --pbrt`.
set -euo pipefail
HERE="$(cd "$(dirname "$0")" && pwd)"
ROOT="$(cd "$HERE/../.." && pwd)"
SRC="${1:-}"
BUILD_DIR="${BUILD_DIR:-$ROOT/build}"
OUT="${2:-$BUILD_DIR/pbrt-v4}"
JOBS="${JOBS:-$(nproc)}"

fail() { echo "pbrt-v4/build.sh: $*" >&2; exit 1; }
[ -n "$SRC" ] || fail "usage: build.sh PBRT_SOURCE_DIR [OUT_DIR]"
[ -f "$SRC/src/pbrt/samplers.h" ] && [ -f "$SRC/src/pbrt/cpu/integrators.cpp" ] \
  || fail "'$SRC' is not a pbrt-v4 source folder (no src/pbrt/samplers.h)"
SRC="$(cd "$SRC" && pwd)"
[ -f "$BUILD_DIR/CMakeCache.txt" ] || fail "no alignset build in $BUILD_DIR: run scripts/build.sh first"
mkdir -p "$OUT"
OUT="$(cd "$OUT" && pwd)"

# 1. alignset's sampler library, installed where pbrt's build finds it.
cmake --build "$BUILD_DIR" -j "$JOBS" --target alignset_sampler > "$OUT/alignset-build.log" 2>&1 \
  || { tail -30 "$OUT/alignset-build.log"; fail "building alignset's sampler library failed"; }
rm -rf "$OUT/alignset"
cmake --install "$BUILD_DIR" --prefix "$OUT/alignset" --component sampler > "$OUT/alignset-install.log" 2>&1 \
  || { tail -30 "$OUT/alignset-install.log"; fail "installing alignset failed (build everything: scripts/build.sh)"; }

# 2. The stamp: pbrt's sources, what of the integration goes into the build, the
# installed library.
stamp="$( { find "$SRC/src" "$SRC/cmake" -type f -printf '%P %s %T@\n' | sort;
            find "$HERE/CMakeLists.txt" "$HERE/aligned-sampler.patch" "$HERE/build.sh" "$HERE/src" "$HERE/standins" \
              -type f -print0 | sort -z | xargs -0 sha256sum;
            find "$OUT/alignset" -type f -print0 | sort -z | xargs -0 sha256sum; } | sha256sum | cut -d' ' -f1)"
if [ -x "$OUT/bin/pbrt" ] && [ "$(cat "$OUT/stamp" 2>/dev/null)" = "$stamp" ]; then
  echo "pbrt-v4/build.sh: $OUT/bin/pbrt is up to date"
  exit 0
fi

# 3. The overlay: patched copies of the files the patch changes, written only
# when their content changes (an unchanged header keeps its time, so nothing
# that includes it rebuilds), the include redirects and stand-ins.
STAGE="$OUT/patch-stage"
rm -rf "$STAGE"
mkdir -p "$STAGE"
patched=(src/pbrt/base/sampler.h src/pbrt/samplers.h src/pbrt/samplers.cpp src/pbrt/cpu/integrators.cpp)
for f in "${patched[@]}"; do
  mkdir -p "$STAGE/$(dirname "$f")"
  cp "$SRC/$f" "$STAGE/$f"
done
(cd "$STAGE" && patch -s -p1 --no-backup-if-mismatch < "$HERE/aligned-sampler.patch") \
  || fail "aligned-sampler.patch does not apply to $SRC (a pbrt-v4 of another commit?)"
put() {  # put FROM TO: copy when the content differs
  mkdir -p "$(dirname "$2")"
  cmp -s "$1" "$2" 2>/dev/null || cp "$1" "$2"
}
for f in "${patched[@]}"; do put "$STAGE/$f" "$OUT/overlay/$f"; done
(cd "$HERE/standins" && find . -type f) | while read -r f; do put "$HERE/standins/$f" "$OUT/overlay/ext/$f"; done
# pbrt's two large generated tables, where the folder lacks them: all-zero
# stand-ins. Their users are pbrt's pmj02bn sampler (refused by the patch in
# such a build) and the dither of 8-bit image output (none here: .exr/.pfm).
mkdir -p "$OUT/overlay/src/pbrt/util"
if [ ! -f "$SRC/src/pbrt/util/bluenoise.cpp" ]; then
  echo "pbrt-v4/build.sh: $SRC lacks src/pbrt/util/bluenoise.cpp: a stand-in of zeros (8-bit output is not dithered)"
  printf '%s\n' '// Stand-in written by alignset integrations/pbrt-v4/build.sh: the source folder lacks the table.' \
    '#include <pbrt/util/bluenoise.h>' 'namespace pbrt {' \
    'PBRT_CONST uint16_t BlueNoiseTextures[NumBlueNoiseTextures][BlueNoiseResolution][BlueNoiseResolution] = {};' \
    '}' > "$STAGE/bluenoise.cpp"
  put "$STAGE/bluenoise.cpp" "$OUT/overlay/src/pbrt/util/bluenoise.cpp"
else
  rm -f "$OUT/overlay/src/pbrt/util/bluenoise.cpp"  # an overlay file is compiled instead of pbrt's
fi
if [ ! -f "$SRC/src/pbrt/util/pmj02tables.cpp" ]; then
  echo "pbrt-v4/build.sh: $SRC lacks src/pbrt/util/pmj02tables.cpp: a stand-in of zeros; this pbrt refuses the pmj02bn sampler"
  printf '%s\n' '// Stand-in written by alignset integrations/pbrt-v4/build.sh: the source folder lacks the table.' \
    '#include <pbrt/util/pmj02tables.h>' 'namespace pbrt {' \
    'PBRT_CONST uint32_t pmj02bnSamples[nPMJ02bnSets][nPMJ02bnSamples][2] = {};' \
    '}' > "$STAGE/pmj02tables.cpp"
  put "$STAGE/pmj02tables.cpp" "$OUT/overlay/src/pbrt/util/pmj02tables.cpp"
else
  rm -f "$OUT/overlay/src/pbrt/util/pmj02tables.cpp"
fi

# 4. pbrt, with ccache where Debian's ccache is installed.
GEN=()
command -v ninja >/dev/null 2>&1 && GEN=(-G Ninja)
LAUNCHER=()
command -v ccache >/dev/null 2>&1 && LAUNCHER=(-DCMAKE_C_COMPILER_LAUNCHER=ccache -DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
echo "pbrt-v4/build.sh: building pbrt-v4 from $SRC into $OUT/pbrt-build (the first build takes minutes; log: $OUT/pbrt-build.log)"
cmake -S "$HERE" -B "$OUT/pbrt-build" "${GEN[@]}" "${LAUNCHER[@]}" -DCMAKE_BUILD_TYPE=Release \
  -DPBRT_SOURCE_DIR="$SRC" -DPBRT_OVERLAY_DIR="$OUT/overlay" -DCMAKE_PREFIX_PATH="$OUT/alignset" \
  > "$OUT/pbrt-configure.log" 2>&1 || { tail -40 "$OUT/pbrt-configure.log"; fail "configuring pbrt failed"; }
if ! cmake --build "$OUT/pbrt-build" -j "$JOBS" --target pbrt > "$OUT/pbrt-build.log" 2>&1; then
  grep -B2 -A12 "error" "$OUT/pbrt-build.log" | head -60
  fail "building pbrt failed (log: $OUT/pbrt-build.log)"
fi
mkdir -p "$OUT/bin"
cp "$OUT/pbrt-build/pbrt" "$OUT/bin/pbrt.new" && mv "$OUT/bin/pbrt.new" "$OUT/bin/pbrt"
echo "$stamp" > "$OUT/stamp"
echo "pbrt-v4/build.sh: built $OUT/bin/pbrt"

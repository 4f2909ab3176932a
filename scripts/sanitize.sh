#!/usr/bin/env bash
# The test suite under sanitizers, in a build directory of its own:
#   scripts/sanitize.sh            AddressSanitizer + UndefinedBehaviorSanitizer (build-asan/)
#   scripts/sanitize.sh thread     ThreadSanitizer (build-tsan/), the threaded suites only
# Extra arguments go to ctest (e.g. -R Scheduler). CUDA is off (nvcc does not
# take these flags); the container test is not run (its binaries are the
# image's own). Suppressions for uninstrumented system libraries, each naming
# its frame and why: scripts/sanitizers/.
set -euo pipefail
cd "$(dirname "$0")/.."
MODE="${1:-address}"
[ $# -gt 0 ] && shift
case "$MODE" in
  address)
    BUILD_DIR="${BUILD_DIR:-build-asan}"
    FLAGS="-fsanitize=address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer -O1 -g"
    export ASAN_OPTIONS="${ASAN_OPTIONS:-detect_leaks=1:abort_on_error=1:strict_string_checks=1}"
    export UBSAN_OPTIONS="${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}"
    export LSAN_OPTIONS="${LSAN_OPTIONS:-suppressions=$PWD/scripts/sanitizers/lsan.supp}"
    # Not these: the consumer builds against the installed package without
    # the sanitizers' runtime, and Debian's python3 cannot load a sanitized
    # extension module (the runtime must come first in the process).
    BUILD_TARGETS=()
    TESTS=(-E "^Package\\.|^Python\\.SamplerOnAnExportedTable")
    ;;
  thread)
    BUILD_DIR="${BUILD_DIR:-build-tsan}"
    FLAGS="-fsanitize=thread -fno-omit-frame-pointer -O1 -g"
    export TSAN_OPTIONS="${TSAN_OPTIONS:-halt_on_error=1:second_deadlock_stack=1:suppressions=$PWD/scripts/sanitizers/tsan.supp}"
    # The threaded parts: scheduler, server, caches, thread pool, the
    # renderer's parallel loops, the sampler library.
    TESTS=(-L "server|e2e|storage|render|sampler")
    # Only what those suites run (their test binaries, the server and the
    # CLI that the end-to-end tests start): the core suite and the rest are
    # single-threaded, and building them under TSan took a third of the run.
    BUILD_TARGETS=(alignset_server_tests alignset_storage_tests alignset_render_tests alignset_sampler_tests
                   alignset_e2e_tests alignset_e2e_timed_tests alignset-server alignset)
    ;;
  *) echo "usage: $0 [address|thread] [ctest arguments]" >&2; exit 2 ;;
esac
bash scripts/install-deps.sh --test
GEN=()
command -v ninja >/dev/null 2>&1 && GEN=(-G Ninja)
cmake -S . -B "$BUILD_DIR" "${GEN[@]}" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DALIGNSET_CUDA=OFF \
  -DALIGNSET_BUILD_TESTS=ON -DALIGNSET_BUILD_BENCH=OFF -DALIGNSET_JEMALLOC=OFF \
  -DCMAKE_CXX_FLAGS="$FLAGS" -DCMAKE_EXE_LINKER_FLAGS="${FLAGS%% -O1*}" -DCMAKE_SHARED_LINKER_FLAGS="${FLAGS%% -O1*}"
TARGET_ARGS=()
for t in "${BUILD_TARGETS[@]}"; do TARGET_ARGS+=(--target "$t"); done
cmake --build "$BUILD_DIR" -j "${JOBS:-$(nproc)}" "${TARGET_ARGS[@]}"
(cd "$BUILD_DIR" && ctest -j "${JOBS:-$(nproc)}" --output-on-failure --timeout 1800 "${TESTS[@]}" "$@")

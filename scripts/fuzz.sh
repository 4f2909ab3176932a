#!/usr/bin/env bash
# The fuzzers of fuzz/ (libFuzzer, Debian's clang, AddressSanitizer and
# UndefinedBehaviorSanitizer on), built in a tree of their own, each run for
# SECONDS from its seed corpus:
#   scripts/fuzz.sh [SECONDS] [FUZZER ...]     default 60 s, every fuzzer
# What a run finds (crash-*, leak-*, timeout-*) goes to build-fuzz/findings/
# and fails the script; the inputs it adds to the corpus stay in
# build-fuzz/corpus/ (fuzz/corpus/ is the seed corpus in the repository).
# A summary line per fuzzer: executions, coverage (cov: edges), corpus size.
set -euo pipefail
cd "$(dirname "$0")/.."
SECONDS_EACH="${1:-60}"
[ $# -gt 0 ] && shift
FUZZERS=("$@")
[ ${#FUZZERS[@]} -eq 0 ] && FUZZERS=(table_file_fuzzer npy_fuzzer point_file_fuzzer blob_fuzzer cache_file_fuzzer request_fuzzer server_flags_fuzzer cli_flags_fuzzer)
BUILD_DIR="${BUILD_DIR:-build-fuzz}"
bash scripts/install-deps.sh --test >/dev/null
FLAGS="-fsanitize=fuzzer-no-link,address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer -O1 -g"
GEN=()
command -v ninja >/dev/null 2>&1 && GEN=(-G Ninja)
LAUNCHER=()
command -v ccache >/dev/null 2>&1 && LAUNCHER=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
CC=clang CXX=clang++ cmake -S . -B "$BUILD_DIR" "${GEN[@]}" "${LAUNCHER[@]}" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DALIGNSET_CUDA=OFF -DALIGNSET_BUILD_TESTS=OFF -DALIGNSET_BUILD_BENCH=OFF -DALIGNSET_BUILD_FUZZERS=ON -DALIGNSET_JEMALLOC=OFF \
  -DCMAKE_CXX_FLAGS="$FLAGS" -DCMAKE_EXE_LINKER_FLAGS="-fsanitize=address,undefined" >/dev/null
cmake --build "$BUILD_DIR" -j "${JOBS:-$(nproc)}" --target "${FUZZERS[@]}"
mkdir -p "$BUILD_DIR/findings"
export ASAN_OPTIONS="${ASAN_OPTIONS:-detect_leaks=1:abort_on_error=1}"
export UBSAN_OPTIONS="${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}"
failed=0
for f in "${FUZZERS[@]}"; do
  mkdir -p "$BUILD_DIR/corpus/$f" "fuzz/corpus/$f"
  log="$BUILD_DIR/findings/$f.log"
  # -rss_limit_mb: a parser that allocates what a header claims fails here.
  # -close_fd_mask=3: the target's own output (the command line's help and
  # error lines) is dropped; libFuzzer's lines and sanitizer reports still
  # reach the log (libFuzzer keeps a copy of stderr for them).
  if ! "$BUILD_DIR/fuzz/$f" -max_total_time="$SECONDS_EACH" -rss_limit_mb=2048 -timeout=10 -print_final_stats=1 \
      -close_fd_mask=3 \
      -artifact_prefix="$BUILD_DIR/findings/$f-" "$BUILD_DIR/corpus/$f" "fuzz/corpus/$f" >"$log" 2>&1; then
    echo "fuzz: $f FOUND SOMETHING (see $log and $BUILD_DIR/findings/$f-*)"
    tail -30 "$log"
    failed=1
  fi
  runs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$log" | tail -1 | grep -o '[0-9]*$' || echo "?")
  cov=$(grep -o 'cov: [0-9]*' "$log" | tail -1 | grep -o '[0-9]*' || echo "?")
  corpus=$(ls "$BUILD_DIR/corpus/$f" | wc -l)
  echo "fuzz: $f ${SECONDS_EACH} s, $runs executions, cov $cov edges, corpus $corpus inputs"
done
exit $failed

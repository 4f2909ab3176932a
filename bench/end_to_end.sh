#!/usr/bin/env bash
# End-to-end optimization time of one set per N (default options): the median
# of REPEATS runs of `alignset optimize`, one after another. DIRS holds the
# arbitrary directions: "30" (default) for a 3-direction set, e.g. "30 100"
# for a 4-direction set.
#
#   [DIRS="30 100"] bench/end_to_end.sh [BUILD_DIR] [ENGINE] [REPEATS] [N...]
set -euo pipefail
BUILD="${1:-build}"
ENGINE="${2:-fast}"
REPEATS="${3:-3}"
shift $(( $# < 3 ? $# : 3 ))
SIZES=("$@")
DIR_FLAGS=()
for d in ${DIRS:-30}; do DIR_FLAGS+=(--dir "$d"); done
[ ${#SIZES[@]} -gt 0 ] || SIZES=(256 1024 4096 16384 65536)
CLI="$BUILD/cli/alignset"
OUT="$(mktemp -d)"
trap 'rm -rf "$OUT"' EXIT
echo "# directions ${DIRS:-30}; $(uptime)"
printf '%8s %10s %12s   %s\n' N iterations median_s "all runs (s)"
for n in "${SIZES[@]}"; do
  times=()
  iters=""
  for _ in $(seq "$REPEATS"); do
    r="$("$CLI" optimize --n "$n" "${DIR_FLAGS[@]}" --engine "$ENGINE" --threads 2 --out "$OUT/set.txt" 2>/dev/null)"
    times+=("$(awk '/^time/{print $2}' <<<"$r")")
    iters="$(awk '/^iterations/{print $2}' <<<"$r")"
  done
  median="$(printf '%s\n' "${times[@]}" | sort -g | awk '{a[NR]=$1} END{print a[int((NR+1)/2)]}')"
  printf '%8s %10s %12s   %s\n' "$n" "$iters" "$median" "${times[*]}"
done

#!/usr/bin/env bash
# End-to-end optimization time of one 3-direction set (θ = 30°, default options)
# per N: the median of REPEATS runs of `alignset optimize`, one after another.
#
#   bench/end_to_end.sh [BUILD_DIR] [ENGINE] [REPEATS] [N...]
set -euo pipefail
BUILD="${1:-build}"
ENGINE="${2:-fast}"
REPEATS="${3:-3}"
shift $(( $# < 3 ? $# : 3 ))
SIZES=("$@")
[ ${#SIZES[@]} -gt 0 ] || SIZES=(256 1024 4096 16384 65536)
CLI="$BUILD/client/alignset"
OUT="$(mktemp -d)"
trap 'rm -rf "$OUT"' EXIT
echo "# $(uptime)"
printf '%8s %10s %12s   %s\n' N iterations median_s "all runs (s)"
for n in "${SIZES[@]}"; do
  times=()
  iters=""
  for _ in $(seq "$REPEATS"); do
    r="$("$CLI" optimize --n "$n" --dir 30 --engine "$ENGINE" --threads 2 --out "$OUT/set.txt" 2>/dev/null)"
    times+=("$(awk '/^time/{print $2}' <<<"$r")")
    iters="$(awk '/^iterations/{print $2}' <<<"$r")"
  done
  median="$(printf '%s\n' "${times[@]}" | sort -g | awk '{a[NR]=$1} END{print a[int((NR+1)/2)]}')"
  printf '%8s %10s %12s   %s\n' "$n" "$iters" "$median" "${times[*]}"
done

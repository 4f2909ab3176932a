#!/bin/bash
# The warm steps at N = 65536 with (version 7) and without (version 8) the
# warm-up half, interleaved, twice: seed 1, root 8 -> theta 11, each run in a
# fresh cache holding only the cold root (from build/bench-cache/lineage).
# Run from the repository root; prints the optimization time of every step.
set -euo pipefail
root_set=build/bench-cache/lineage/set-9c4e9f5e59e9c2dd.bin   # cold, N = 65536, theta 8, seed 1
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
for rep in 1 2; do
  for ww in 0.5 0; do
    d="$tmp/${ww}_$rep"
    mkdir -p "$d"
    cp "$root_set" "$d/"
    build/bench/alignset_integrand_family --cache "$d" --seeds 1 --first-seed 1 --n 65536 --theta 11 \
      --warm-root 8 --scrambles 2 --shifts 1 --offsets 1 --gaussian-shifts 1 --construction warm \
      --warm-warmup "$ww" --out /dev/null 2>&1 | grep "optimized N" | sed "s/^/ww=$ww rep=$rep /"
  done
done

#!/bin/bash
# The integrand-family tables (docs/results.md, "Integrand family"):
# alignset's profile and the supplement's (algorithm version 2) against
# Owen-Sobol (16 scrambles), same integrands and shifts, N = 256..4096 at five
# angles, two-direction sets, the larger N with fewer seeds, and the exact
# Eq. 18 variance beside the Monte Carlo figure. Sets and baselines are cached
# in $CACHE, so an interrupted run resumes.
#   bench/integrand_family.sh [BUILD_DIR] [OUT_DIR]
set -euo pipefail
build=${1:-build}
out=${2:-bench/results}
CACHE=${CACHE:-$build/bench-cache/family}
fam="$build/bench/alignset_integrand_family"
mkdir -p "$out" "$CACHE"
run() { local name=$1; shift; "$fam" --cache "$CACHE" --out "$out/$name.tsv" "$@" | tee "$out/$name.txt"; }
part=${PART:-all}
if [[ $part == all || $part == main ]]; then
  for profile in current supplement; do
    run "family_${profile}" --profile $profile --n 256,1024,4096 --theta 10,30,45,63,82 --seeds 4
  done
fi
if [[ $part == all || $part == two ]]; then
  for profile in current supplement; do
    run "family_two_${profile}" --profile $profile --n 1024,4096 --theta 30 --theta2 100 --seeds 2
  done
fi
if [[ $part == all || $part == exact ]]; then
  run family_exact --n 1024 --theta 30 --seeds 2 --exact
fi
if [[ $part == all || $part == large ]]; then
  for profile in current supplement; do
    run "family_large_${profile}" --profile $profile --n 16384,65536 --theta 30 --seeds 1 \
      --shifts 256 --offsets 4
  done
fi

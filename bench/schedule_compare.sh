#!/usr/bin/env bash
# Optimizer schedules compared at a fixed iteration budget: mean CP variance on
# the aligned step edge (θ = 30°, N = 4096, `alignset evaluate`) over seeds
# 1..SEEDS, as a ratio to REFERENCE (the converged mean printed by
# bench/time_to_quality.py; default: its N = 4096 figure).
#
#   bench/schedule_compare.sh [BUILD_DIR] [SEEDS] [REFERENCE]
set -euo pipefail
BUILD="${1:-build}"
SEEDS="${2:-4}"
REF="${3:-1.4653e-7}"
CLI="$BUILD/cli/alignset"
OUT="$(mktemp -d)"
trap 'rm -rf "$OUT"' EXIT

run() {  # label, optimize flags...
  local label="$1"; shift
  local vs=() its=()
  for s in $(seq "$SEEDS"); do
    r="$("$CLI" optimize --n 4096 --dir 30 --engine fast --threads 2 --seed "$s" \
         --out "$OUT/set.txt" "$@" 2>/dev/null)"
    its+=("$(awk '/^iterations/{print $2}' <<<"$r")")
    vs+=("$("$CLI" evaluate "$OUT/set.txt" --normal 30 | awk '/^variance  /{print $2}')")
  done
  printf '%s\n' "${vs[@]}" | awk -v label="$label" -v ref="$REF" -v its="${its[*]}" \
    '{s += $1; if ($1 > m) m = $1}
     END {printf "%-44s %10.4e %7.3f %7.3f   %s\n", label, s / NR, s / NR / ref, m / ref, its}'
}

echo "# N=4096 θ=30 seeds 1..$SEEDS, reference (converged mean) $REF; $(uptime)"
printf '%-44s %10s %7s %7s   %s\n' schedule "mean var" ratio worst iterations
run "default (c=4N, lr 0.05/|v|max, 1000 it)"
run "c=N, 1000 it" --sw-weight 4096
run "c=N, 3000 it" --sw-weight 4096 --max-iterations 3000
run "paper lr 1e-5 (c=4N), 1000 it" --learning-rate 1e-5 --max-iterations 1000
run "paper lr 1e-5 (c=4N), 3000 it" --learning-rate 1e-5 --max-iterations 3000
run "paper lr 1e-5 (c=4N), 10000 it" --learning-rate 1e-5 --max-iterations 10000
run "paper lr 1e-5, c=10, 10000 it" --learning-rate 1e-5 --sw-weight 10 --max-iterations 10000

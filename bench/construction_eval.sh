#!/usr/bin/env bash
# Constructions side by side, judged by bench/construction_eval.py (NumPy,
# no code shared with the core): Owen-Sobol (16 scrambles), the aligned
# lattice (4 realizations), the tent-folded lattice (64 realizations, its own
# randomization: construction_eval.py --randomized), the aligned net (2
# realizations) and the optimized set (one seed), on edges at
# theta + 0 / 0.5 / 1 / 2 degrees, 1024 seeded Gaussians and two ramps,
# with and without Cranley-Patterson shifts.
#
#   N=256,1024,4096 THETA=10,30,45,63,82 bash bench/construction_eval.sh [OUT.tsv]
#   CONSTRUCTIONS="lattice tent-lattice net optimized" (the default): which to
#   measure beside Owen-Sobol (the evaluator's shifts and Gaussians are seeded:
#   Owen-Sobol's rows are the same in every run).
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD_DIR="${BUILD_DIR:-build}"
CLI="$BUILD_DIR/cli/alignset"
N="${N:-256,1024,4096}"
THETA="${THETA:-10,30,45,63,82}"
SHIFTS="${SHIFTS:-256}"
GAUSSIANS="${GAUSSIANS:-1024}"
# Two-direction sets, A:B pairs, judged on the edges of both directions;
# PAIRS= (set and empty) measures none.
PAIRS="${PAIRS-30:120,20:65}"
CONSTRUCTIONS="${CONSTRUCTIONS:-lattice tent-lattice net optimized}"
OUT="${1:-bench/results/construction_eval.tsv}"
WORK="$BUILD_DIR/construction-eval"
mkdir -p "$WORK"
: > "$OUT"
has() { [[ " $CONSTRUCTIONS " == *" $1 "* ]]; }
# make_args TAG SUFFIX NETS DIR...: the sets of every construction measured,
# for N = $n and the directions DIR, in files named by TAG (a set's file
# NAME$TAG[_SEED].txt), labelled NAME$SUFFIX; NETS net realizations. Sets
# `args`, the evaluator's labels and files.
make_args() {
  local tag=$1 suffix=$2 nets=$3
  shift 3
  local dirs=()
  for d in "$@"; do dirs+=(--dir "$d"); done
  args=()
  if has lattice; then
    for s in 1 2 3 4; do
      "$CLI" optimize -n "$n" "${dirs[@]}" --construction lattice -s "$s" -o "$WORK/lat${tag}_$s.txt" >/dev/null
    done
    args+=(--label "lattice$suffix" "$WORK"/lat${tag}_*.txt)
  fi
  if has tent-lattice; then
    "$CLI" optimize -n "$n" "${dirs[@]}" --construction tent-lattice -m 64 -o "$WORK/tent$tag.txt" >/dev/null
    args+=(--randomized "tent-lattice$suffix" "$WORK/tent$tag.txt")
  fi
  if has net; then
    for s in $(seq 1 "$nets"); do
      [ -f "$WORK/net${tag}_$s.txt" ] || "$CLI" optimize -n "$n" "${dirs[@]}" --construction net -s "$s" -o "$WORK/net${tag}_$s.txt" >/dev/null
    done
    args+=(--label "net$suffix" "$WORK"/net${tag}_*.txt)
  fi
  if has optimized; then
    [ -f "$WORK/opt$tag.txt" ] || "$CLI" optimize -n "$n" "${dirs[@]}" -s 1 -o "$WORK/opt$tag.txt" >/dev/null 2>&1
    args+=(--label "optimized$suffix" "$WORK/opt$tag.txt")
  fi
}
for n in ${N//,/ }; do
  for s in $(seq 1 16); do
    [ -f "$WORK/os_${n}_$s.txt" ] || "$CLI" sample owen-sobol -n "$n" -s "$s" -o "$WORK/os_${n}_$s.txt" >/dev/null
  done
  for t in ${THETA//,/ }; do
    make_args "_${n}_$t" "" 2 "$t"
    /usr/bin/python3 bench/construction_eval.py --theta "$t" --shifts "$SHIFTS" --gaussians "$GAUSSIANS" \
      --label owen-sobol "$WORK"/os_${n}_*.txt "${args[@]}" --out "$OUT.part" | tail -n +2
  done
  for pair in ${PAIRS//,/ }; do
    a="${pair%%:*}"; b="${pair##*:}"
    make_args "2_${n}_${a}_$b" "-2dir($a,$b)" 1 "$a" "$b"
    for t in "$a" "$b"; do
      /usr/bin/python3 bench/construction_eval.py --theta "$t" --shifts "$SHIFTS" --gaussians "$GAUSSIANS" \
        --label owen-sobol "$WORK"/os_${n}_*.txt "${args[@]}" --out "$OUT.part" | tail -n +2
    done
  done
done
# One header line, then the rows.
{ head -1 "$OUT.part"; grep -v '^sampler' "$OUT.part"; } > "$OUT"
rm -f "$OUT.part"
echo "construction_eval: wrote $OUT"

#!/usr/bin/env bash
# The pre-pass size and the lattice's window at one N, every sample counted:
# renders aligned-lattice+reuse with the pre-pass KIND M (edgesM, the
# pixel's own samples, unless KIND=nedges: pooled with the neighbours') for
# each M and each window W (degrees either side of the estimated θ a lattice
# is chosen for), and the four baselines at N + M, on each scene seed; then
# one table (bench/render/prepass_sweep.py) of Owen-Sobol's and the best
# baseline's edge MSE at N + M over the lattice's. Two-direction lattices up
# to TWO_MAX_N (default 1024).
#
#   bash bench/render/prepass_sweep.sh                      # N = 256, seeds 1 2 3
#   N=1024 MS="64 256" WINDOWS="1 2" SEEDS="4 5" bash bench/render/prepass_sweep.sh
#   N=4096 MS="256 512" WINDOWS=1 KIND=nedges TWO_MAX_N=65536 bash bench/render/prepass_sweep.sh
set -euo pipefail
cd "$(dirname "$0")/../.."
BUILD_DIR="${BUILD_DIR:-build}"
SEEDS="${SEEDS:-1 2 3}"
N="${N:-256}"
MS="${MS:-32 64 128}"
WINDOWS="${WINDOWS:-0.5 1 2 3}"
KIND="${KIND:-edges}"
TWO_MAX_N="${TWO_MAX_N:-1024}"
RAW="${RAW:-$BUILD_DIR/render-sweep$N}"
OUT="${OUT:-bench/results/render_prepass_sweep$N.md}"
. bench/render/render_server.sh
mkdir -p "$RAW"
start_render_server
for seed in $SEEDS; do
  for m in $MS; do
    common=(--two-max-n "$TWO_MAX_N" --prepass "$KIND$m")
    for w in $WINDOWS; do
      seed_render_bench "$seed" "${common[@]}" --out "$RAW/s$seed-m$m-w$w" --n "$N" \
        --samplers owen-sobol,aligned-lattice+reuse --lattice-window "$w"
    done
    seed_render_bench "$seed" "${common[@]}" --out "$RAW/s$seed-m$m-counted" --n $((N + m)) \
      --samplers owen-sobol,pmj02bn,rank1-lattice,screen-space-rank1
  done
done
/usr/bin/python3 bench/render/prepass_sweep.py --raw "$RAW" --n "$N" --seeds "$SEEDS" --ms "$MS" \
  --windows "$WINDOWS" --kind "$KIND" --out "$OUT"
echo "prepass_sweep: wrote $OUT"

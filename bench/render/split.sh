#!/usr/bin/env bash
# Where the rendered edge error goes (issue 26): renders both scenes of each
# seed with a ladder of samplers that remove one cause at a time (the
# estimated direction, the second direction, the per-pixel shift, the
# optimized set's strip floor), and splits the edge error by pixel type
# (bench/render/error_split.py): a table and a figure.
#
#   bash bench/render/split.sh                          # seeds 1 2 3, N = 256, 1024, 4096
#   SEEDS="4" N=1024 bash bench/render/split.sh
set -euo pipefail
cd "$(dirname "$0")/../.."
BUILD_DIR="${BUILD_DIR:-build}"
SEEDS="${SEEDS:-1 2 3}"
N="${N:-256,1024,4096}"
SAMPLERS="${SAMPLERS:-owen-sobol,aligned,aligned-exact,aligned-exact-1dir,aligned-exact-noshift,aligned-lattice,aligned-lattice-exact}"
RAW="${RAW:-$BUILD_DIR/render-split}"
OUT="${OUT:-bench/results/render_error_split.md}"
FIGURE="${FIGURE:-bench/results/render_error_split.png}"
TWO_MAX_N="${TWO_MAX_N:-1024}"
THREADS="${THREADS:-2}"
. bench/render/render_server.sh
PREPASS="${PREPASS:-$(default_prepass)}"

mkdir -p "$RAW"
start_render_server
echo "split: alignset-server on $ADDR, pre-pass $PREPASS"
for seed in $SEEDS; do
  seed_render_bench "$seed" --two-max-n "$TWO_MAX_N" --prepass "$PREPASS" --out "$RAW/seed$seed" \
    --n "$N" --samplers "$SAMPLERS"
done
/usr/bin/python3 bench/render/error_split.py --raw "$RAW" --seeds "$SEEDS" --n "$N" --out "$OUT" \
  --figure "$FIGURE"
echo "split: wrote $OUT and $FIGURE"

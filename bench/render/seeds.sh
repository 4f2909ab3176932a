#!/usr/bin/env bash
# The rendered comparison over several scene seeds, with every sample counted:
# renders both scenes of each seed with the samplers below at N = 256, 1024
# and 4096 (render_bench against its own loopback server), then renders the
# samplers that need no pre-pass again at N + P (P: the evaluations of the
# estimated-direction samplers' pre-pass, read from render_bench's
# estimator.csv; 256 for the default edges256), and writes one table
# (bench/render/seed_table.py).
#
#   bash bench/render/seeds.sh                       # seeds 1 2 3
#   SEEDS="4 5" N=1024 bash bench/render/seeds.sh    # others
#   PREPASS=edges64 N=256 SAMPLERS=owen-sobol,aligned-lattice,aligned-lattice+reuse bash bench/render/seeds.sh
#   SCENES=shadow PREPASS=nedges256l N=4096 bash bench/render/seeds.sh   # one scene, its own pre-pass
#
# Two-direction sets up to TWO_MAX_N: by default 1024 when the optimized
# sets are among the samplers (`aligned*`: filling their pairs at 4096 takes
# about 40 minutes per seed), and every N when only lattices are aligned
# (chosen locally in seconds), as `alignset render` does; the policy is the
# same for every aligned sampler, lattices included.
set -euo pipefail
cd "$(dirname "$0")/../.."
BUILD_DIR="${BUILD_DIR:-build}"
SEEDS="${SEEDS:-1 2 3}"
N="${N:-256,1024,4096}"
SCENES="${SCENES:-antialias,shadow}"
SAMPLERS="${SAMPLERS:-owen-sobol,pmj02bn,rank1-lattice,screen-space-rank1,aligned,aligned+reuse,aligned-exact,aligned-lattice,aligned-lattice+reuse,aligned-lattice+unbiased,aligned-lattice-exact}"
COUNTED="${COUNTED:-owen-sobol,pmj02bn,rank1-lattice,screen-space-rank1}"
RAW="${RAW:-$BUILD_DIR/render-seeds}"
OUT="${OUT:-bench/results/render_seeds.md}"
optimized_sets=0
for s in ${SAMPLERS//,/ }; do
  [[ $s == aligned* && $s != aligned-lattice* && $s != aligned-tent-lattice* ]] && optimized_sets=1
done
if (( optimized_sets )); then TWO_MAX_N="${TWO_MAX_N:-1024}"; else TWO_MAX_N="${TWO_MAX_N:-65536}"; fi
THREADS="${THREADS:-2}"
# The direction estimator's pre-pass (render/spectral_estimator.h); what it
# costs a pixel is read from the estimator.csv render_bench writes.
. bench/render/render_server.sh
PREPASS="${PREPASS:-$(default_prepass)}"

mkdir -p "$RAW"
start_render_server
echo "seeds: alignset-server on $ADDR"

for seed in $SEEDS; do
  common=(--two-max-n "$TWO_MAX_N" --prepass "$PREPASS" --scenes "$SCENES")
  seed_render_bench "$seed" "${common[@]}" --out "$RAW/seed$seed" --n "$N" \
    --samplers "$SAMPLERS"
  counted_n=$(/usr/bin/python3 -c "
import csv, sys
evals = {int(r['evaluations']) for r in csv.DictReader(open(sys.argv[1]))}
assert len(evals) == 1, evals
p = evals.pop()
print(','.join(str(int(n) + p) for n in sys.argv[2].split(',')))" "$RAW/seed$seed/estimator.csv" "$N")
  seed_render_bench "$seed" "${common[@]}" --out "$RAW/seed$seed-counted" \
    --n "$counted_n" --samplers "$COUNTED"
done
/usr/bin/python3 bench/render/seed_table.py --raw "$RAW" --seeds "$SEEDS" --n "$N" --out "$OUT"
echo "seeds: wrote $OUT"

#!/bin/bash
# The key lineage's sets against the cold ones on the integrand family
# (docs/results.md, "Filling the space: the key lineage"). For each case the
# set for theta is reached from the cold set at theta - 3 by three one-degree
# warm steps (the lineage's deepest chain since algorithm version 7; the
# service's WarmStartOptions, alignset_integrand_family --construction warm)
# and compared with the cold set for theta of the same seed. The table gives,
# per member, the geometric mean over seeds of warm / cold with a 90%
# bootstrap interval, and beside it the measurement's null: cold sets of
# other seeds against the cold sets (seed s + S/2 against seed s), the ratio
# two equally good sets show. Members evaluated without a shift swing by
# factors between seeds; their cells say little (the null shows how little).
# At N = 65536 (one direction, 6 seeds; two directions, SEEDS_TWO_LARGE seeds, default 4:
# with one seed the centred Gaussian's null was 0.31) each set is evaluated once per CP shift seed (SHIFT_SEEDS) and
# the mean taken: with 64 shifts per Gaussian one evaluation of the CP
# Gaussians moved by up to 22% under another shift seed, as much as the
# differences being measured (bench/results/lineage_warmup_large_n.md).
#   bench/lineage_quality.sh [BUILD_DIR] [OUT_DIR]    (SUMMARY_ONLY=1: re-read OUT_DIR's tsv files)
#   ANGLES=1: other angles at N = 4096 instead (one direction at 10 and 82 deg, two at 12 and 80,
#   near the axes, where the chain from theta - 3 runs beside an axis strip; two at 12 and 50 and
#   at 20 and 80, one of them near an axis), 36 seeds each (about 75 min);
#   OUT_DIR then defaults to bench/results/lineage_quality_angles.
#   SEEDS=S (default 12) for the N = 4096 two-direction case, SEEDS_ONE (default 36) for the
#   one-direction one: with 12 seeds its axis edge at 0 deg (1.078, interval 0.99-1.16) could not
#   be told from the 5% the lineage may lose.
#   KEEP=1: keep OUT_DIR's tsv files and evaluate only what is missing (a long run resumed, or
#   more seeds added to one case).
set -euo pipefail
build=${1:-build}
out=${2:-bench/results/lineage_quality${ANGLES:+_angles}}
cache=${CACHE:-$build/bench-cache/lineage}
seeds=${SEEDS:-12}
seeds_one=${SEEDS_ONE:-36}
seeds_two_large=${SEEDS_TWO_LARGE:-4}
fam="$build/bench/alignset_integrand_family"
mkdir -p "$out" "$cache"
run() {  # tag seeds args...   (SHIFT_SEEDS="A B ...": evaluate each set once per CP shift seed)
  local tag=$1 count=$2
  shift 2
  for s in $(seq 1 "$count"); do
    for ss in ${SHIFT_SEEDS:-12345}; do
      local x=""
      [[ -n ${SHIFT_SEEDS:-} ]] && x="_x$ss"
      for kind in cold:optimized warm:warm; do
        local file="$out/${tag}_${kind%%:*}_s$s$x.tsv"
        [[ -n ${KEEP:-} && -s $file ]] && continue
        "$fam" --cache "$cache" --seeds 1 --first-seed "$s" "$@" --shift-seed "$ss" \
          --construction "${kind##*:}" --out "$file" > /dev/null
      done
    done
  done
}
[[ -z ${SUMMARY_ONLY:-} && -z ${KEEP:-} ]] && rm -f "$out"/*.tsv
if [[ -z ${SUMMARY_ONLY:-} && -n ${ANGLES:-} ]]; then
  run n4096one10 "$seeds_one" --n 4096 --theta 10 --warm-root 7
  run n4096one82 "$seeds_one" --n 4096 --theta 82 --warm-root 79
  run n4096two12 "$seeds_one" --n 4096 --theta 12 --theta2 80 --warm-root 9
  run n4096two12x50 "$seeds_one" --n 4096 --theta 12 --theta2 50 --warm-root 9
  run n4096two20x80 "$seeds_one" --n 4096 --theta 20 --theta2 80 --warm-root 17
elif [[ -z ${SUMMARY_ONLY:-} ]]; then
  run n4096one "$seeds_one" --n 4096 --theta 40 --warm-root 37
  run n4096two "$seeds" --n 4096 --theta 40 --theta2 100 --warm-root 37
  run n16384one 2 --n 16384 --theta 11 --warm-root 8 --scrambles 2 --shifts 512 --gaussian-shifts 64
  large_shift_seeds="12345 777 778 779"
  SHIFT_SEEDS=$large_shift_seeds \
    run n65536one 6 --n 65536 --theta 11 --warm-root 8 --scrambles 2 --shifts 512 --gaussian-shifts 64
  # Two directions at 65536 (about 25 min a seed).
  SHIFT_SEEDS=$large_shift_seeds run n65536two "$seeds_two_large" \
    --n 65536 --theta 11 --theta2 100 --warm-root 8 --scrambles 2 --shifts 512 --gaussian-shifts 64
fi
/usr/bin/python3 - "$out" <<'PY' | tee "$out.md"
import collections, glob, math, os, random, re, sys
out = sys.argv[1]
random.seed(1)
tags = sorted({os.path.basename(f).split('_')[0] for f in glob.glob(os.path.join(out, '*_s*.tsv'))},
              key=lambda t: (int(re.match(r'n(\d+)', t).group(1)), t))
def gm(logs):
    return math.exp(sum(logs) / len(logs))
def cell(logs):
    if not logs:
        return ''
    if len(logs) < 4:
        return '%.2f (%d)' % (gm(logs), len(logs))
    boot = sorted(gm([random.choice(logs) for _ in logs]) for _ in range(2000))
    return '%.3f [%.2f, %.2f] (%d)' % (gm(logs), boot[100], boot[1899], len(logs))
table = collections.OrderedDict()
columns = []
pattern = re.compile(r'^(\w+?)_(cold|warm)_s(\d+)(?:_x(\d+))?\.tsv$')
for tag in tags:
    # rows[member][kind][seed]: the mean over the set's evaluations (one per CP shift seed).
    sums = collections.defaultdict(lambda: collections.defaultdict(lambda: collections.defaultdict(list)))
    for f in glob.glob(os.path.join(out, tag + '_*_s*.tsv')):
        match = pattern.match(os.path.basename(f))
        if not match:
            continue
        kind, seed = match.group(2), int(match.group(3))
        for line in open(f).read().splitlines()[1:]:
            t = line.split('\t')
            sums[t[2]][kind][seed].append(float(t[3]))
    rows = {m: {k: {s: sum(v) / len(v) for s, v in d.items()} for k, d in kinds.items()}
            for m, kinds in sums.items()}
    columns += [tag + ': warm / cold', tag + ': null, cold / cold']
    for member, d in rows.items():
        cold, warm = d.get('cold', {}), d.get('warm', {})
        common = sorted(set(cold) & set(warm))
        ratios = [math.log(warm[s] / cold[s]) for s in common]
        seeds = sorted(cold)
        half = len(seeds) // 2
        null = [math.log(cold[seeds[i + half]] / cold[seeds[i]]) for i in range(half)]
        table.setdefault(member, {})[tag + ': warm / cold'] = cell(ratios)
        table.setdefault(member, {})[tag + ': null, cold / cold'] = cell(null)
print('| member | ' + ' | '.join(columns) + ' |')
print('|---|' + '---:|' * len(columns))
for member, cells in table.items():
    print('| %s | %s |' % (member, ' | '.join(cells.get(c, '') for c in columns)))
PY

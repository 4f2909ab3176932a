#!/bin/bash
# The key lineage's sets against the cold ones on the integrand family
# (docs/results.md, "Filling the space: the key lineage"): for each case the
# set for theta is made cold and reached by one-degree warm steps from the
# cold set at the root (alignset_integrand_family --construction warm, the
# service's WarmStartOptions), per seed; the table is the geometric mean over
# seeds of warm / cold of the same seed for every member. A control column
# (CONTROL tags) puts the measurement's own noise beside it: the cold set
# stopped 10 iterations early against the cold set.
#   bench/lineage_quality.sh [BUILD_DIR] [OUT_DIR]    (SUMMARY_ONLY=1: re-read OUT_DIR's tsv files)
set -euo pipefail
build=${1:-build}
out=${2:-bench/results/lineage_quality}
cache=${CACHE:-$build/bench-cache/lineage}
fam="$build/bench/alignset_integrand_family"
mkdir -p "$out" "$cache"
run() {  # tag seeds args...
  local tag=$1 seeds=$2
  shift 2
  for s in $(seq 1 "$seeds"); do
    "$fam" --cache "$cache" --seeds 1 --first-seed "$s" "$@" --out "$out/${tag}_cold_s$s.tsv" > /dev/null
    "$fam" --cache "$cache" --seeds 1 --first-seed "$s" "$@" --construction warm \
      --out "$out/${tag}_warm_s$s.tsv" > /dev/null
  done
}
if [[ -z ${SUMMARY_ONLY:-} ]]; then
  run n256two 4 --n 256 --theta 40 --theta2 100 --warm-root 30
  run n1024one 4 --n 1024 --theta 17 --warm-root 7
  run n1024two 4 --n 1024 --theta 40 --theta2 100 --warm-root 30
  run n4096one 4 --n 4096 --theta 40 --warm-root 30
  run n4096two 4 --n 4096 --theta 40 --theta2 100 --warm-root 30
  for s in 1 2 3 4; do
    "$fam" --cache "$cache" --seeds 1 --first-seed "$s" --n 4096 --theta 40 --theta2 100 \
      --iterations 1490 --out "$out/n4096two_control_s$s.tsv" > /dev/null
  done
  run n16384one 1 --n 16384 --theta 8 --warm-root 7 --scrambles 2 --shifts 512
  run n65536one 1 --n 65536 --theta 8 --warm-root 7 --scrambles 2 --shifts 512
fi
/usr/bin/python3 - "$out" <<'PY'
import collections, glob, math, os, sys
out = sys.argv[1]
tags = sorted({os.path.basename(f).split('_')[0] for f in glob.glob(os.path.join(out, '*_s*.tsv'))},
              key=lambda t: (int(t[1:].rstrip('onetwo')), t))
table = collections.OrderedDict()
for tag in tags:
    rows = collections.defaultdict(lambda: collections.defaultdict(dict))
    for f in glob.glob(os.path.join(out, tag + '_*_s*.tsv')):
        kind = os.path.basename(f).split('_')[1]
        seed = f.rsplit('_s', 1)[1][:-4]
        for line in open(f).read().splitlines()[1:]:
            t = line.split('\t')
            rows[t[2]][kind][seed] = float(t[3])
    for member, d in rows.items():
        for kind, column in (('warm', tag), ('control', tag + ' control')):
            common = sorted(set(d.get('cold', {})) & set(d.get(kind, {})))
            if common:
                g = math.exp(sum(math.log(d[kind][s] / d['cold'][s]) for s in common) / len(common))
                table.setdefault(member, {})[column] = '%.2f (%d)' % (g, len(common))
columns = [c for t in tags for c in (t, t + ' control') if any(c in cells for cells in table.values())]
print('| member | ' + ' | '.join(columns) + ' |')
print('|---|' + '---:|' * len(columns))
for member, cells in table.items():
    print('| %s | %s |' % (member, ' | '.join(cells.get(c, '') for c in columns)))
PY

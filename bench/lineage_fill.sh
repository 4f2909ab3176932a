#!/bin/bash
# The time to fill the key spaces with the key lineage (the server's default
# warm budget; docs/method.md, "Filling the space: the key lineage"), each on
# a fresh cache through a real server on loopback:
#   - the 46 one-direction keys at N = 4096, whole (wall clock);
#   - two-direction keys at N = 4096: the box phi1 in 26..34, phi2 in 56..64
#     around the root (30, 60) (45 distinct canonical keys, all in that
#     root's subtree, so the fill is the root once and every other key warm);
#   - N = 65536: a root and one child, one and two directions.
# The whole two-direction space is extrapolated from the server log's
# per-set seconds: 50 roots x the median cold set + 4091 x the mean warm set
# (a whole-space precompute optimizes each key exactly once, roots first).
#   bench/lineage_fill.sh [BUILD_DIR] [OUT_DIR]     (SUMMARY_ONLY=1: re-read the logs in $LOGS)
set -euo pipefail
build=${1:-build}
out=${2:-bench/results}
logs=${LOGS:-$build/lineage-fill}
if [[ -z ${SUMMARY_ONLY:-} ]]; then
  rm -rf "$logs"
  mkdir -p "$logs"
  server_pid=
  start() {
    "$build/server/alignset-server" --listen "127.0.0.1:$1" --db "$logs/$2.db" --log-level info \
      > "$logs/$2.log" 2>&1 &
    server_pid=$!
    sleep 1
  }
  stop() { kill "$server_pid"; wait "$server_pid" || true; }
  timed() {
    local name=$1 port=$2
    shift 2
    local t0
    t0=$(date +%s.%N)
    "$build/client/alignset" precompute --server "127.0.0.1:$port" "$@" > "$logs/$name.out" 2>&1
    echo "$name $(echo "$(date +%s.%N) - $t0" | bc)" >> "$logs/wall.txt"
  }
  start 50981 one4096
  timed one4096 50981 -n 4096 --space 1dir
  stop
  keys=()
  for a in $(seq 26 34); do for b in $(seq 56 64); do keys+=(--key "$a,$b"); done; done
  start 50982 two4096
  timed two4096 50982 -n 4096 --space keys "${keys[@]}"
  stop
  start 50983 one65536
  timed one65536 50983 -n 65536 --space keys --key 7 --key 8
  stop
  start 50984 two65536
  timed two65536 50984 -n 65536 --space keys --key 30,60 --key 31,60
  stop
fi
mkdir -p "$out"
/usr/bin/python3 - "$logs" > "$out/lineage_fill.md" <<'EOF'
import re, statistics, sys, os
logs = sys.argv[1]
wall = dict(l.split() for l in open(os.path.join(logs, 'wall.txt')))
def sets(name):
    cold, warm = [], []
    for line in open(os.path.join(logs, name + '.log')):
        if 'optimize done' not in line:
            continue
        s = float(re.search(r' ([0-9.]+) s$', line.strip()).group(1))
        # The log's start line says which ones were warm; the budget tells them apart too.
        it = int(re.search(r'iterations=(\d+)', line).group(1))
        (warm if it < 0.5 * max_budget(name) else cold).append(s)
    return cold, warm
def max_budget(name):
    return max(int(m) for m in re.findall(r'max_iterations=(\d+)', open(os.path.join(logs, name + '.log')).read()))
print('# Filling the key spaces with the key lineage: `bash bench/lineage_fill.sh`\n')
print('2 cores; server defaults (one worker, every core, warm budget 0.13); a fresh cache per row. '
      'Seconds per set from the server log (`optimize done`), wall clock from the precompute call.\n')
print('| what | wall s | cold sets | median cold s | warm sets | mean warm s | median warm s |')
print('|---|---:|---:|---:|---:|---:|---:|')
rows = {}
for name, what in [('one4096', '1 dir, N = 4096, the 46 keys'),
                   ('two4096', '2 dir, N = 4096, 45 keys around the root (30, 60)'),
                   ('one65536', '1 dir, N = 65536, the root 7 and its child 8'),
                   ('two65536', '2 dir, N = 65536, the root (30, 60) and its child (31, 60)')]:
    if name not in wall:
        continue
    cold, warm = sets(name)
    rows[name] = (cold, warm)
    med = lambda v: '%.2f' % statistics.median(v) if v else '-'
    mean = lambda v: '%.3f' % statistics.mean(v) if v else '-'
    print('| %s | %.1f | %d | %s | %d | %s | %s |' % (what, float(wall[name]), len(cold), med(cold), len(warm), mean(warm), med(warm)))
print()
if 'two4096' in rows:
    cold, warm = rows['two4096']
    total = 50 * statistics.median(cold) + 4091 * statistics.mean(warm)
    print('Whole two-direction space at N = 4096: 50 roots x %.2f s + 4091 x %.3f s = **%.0f s (%.1f min)**.' %
          (statistics.median(cold), statistics.mean(warm), total, total / 60))
for name, keys, roots in [('one65536', 46, 3), ('two65536', 4141, 50)]:
    if name in rows and rows[name][0] and rows[name][1]:
        cold, warm = rows[name]
        avg = (roots * statistics.median(cold) + (keys - roots) * statistics.mean(warm)) / keys
        print('\nN = 65536, %d keys: %d roots x %.1f s + %d x %.1f s = %.1f s a set on average over the space.' %
              (keys, roots, statistics.median(cold), keys - roots, statistics.mean(warm), avg))
EOF
cat "$out/lineage_fill.md"

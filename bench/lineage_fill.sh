#!/bin/bash
# The time to fill the key spaces with the key lineage (the server's default
# warm budget; docs/method.md, "Filling the space: the key lineage"), each on
# a fresh cache through a real server on loopback:
#   - the 46 one-direction keys at N = 4096, whole (wall clock);
#   - two-direction keys at N = 4096: the box phi1 in 26..34, phi2 in 56..64
#     (45 distinct canonical keys: 4 roots, the rest warm from them or from
#     ancestors just outside, which the fill computes first);
#   - the same at N = 1024, and N = 16384 and 65536: a root and one child,
#     one direction (8 and 7) and two (31, 58 and 32, 58);
#   - the two-direction space at N = 4096 sampled: shard 0 of 20 (208 keys,
#     a contiguous block of the lineage order, as a precompute shard takes
#     it), extrapolated to 4141 keys;
#   - with ROWS=full4096 (not in the default rows: about 40 min): the whole
#     two-direction space at N = 4096, one `alignset precompute --space 2dir`;
#   - with ROWS="whole65536 whole65536w2" (about 50 min): the 46 one-direction
#     keys at N = 65536, whole.
# A row name ending in w2 runs the server with two workers of one thread
# each (--workers 2 --threads-per-worker 1: two keys side by side, a key
# waiting while its parent runs) instead of one worker on both cores.
# The whole two-direction space is extrapolated from the server log's
# per-set seconds: 226 roots x the median cold set + 3915 x the mean warm
# set (the counts of core/align/key_lineage.h; a whole-space precompute
# optimizes each key exactly once, roots first).
#   bench/lineage_fill.sh [BUILD_DIR] [OUT_DIR]
# SUMMARY_ONLY=1: re-read the logs in $LOGS; ROWS="one4096 two1024 ...": run
# only these rows and keep the other rows' logs.
set -euo pipefail
build=${1:-build}
out=${2:-bench/results}
logs=${LOGS:-$build/lineage-fill}
rows=${ROWS:-one1024 two1024 one4096 two4096 shard4096 one16384 two16384 one65536 two65536}
if [[ -z ${SUMMARY_ONLY:-} ]]; then
  [[ -z ${ROWS:-} ]] && rm -rf "$logs"
  mkdir -p "$logs"
  server_pid=
  start() {  # port row [server flags]
    rm -f "$logs/$2.db"*
    "$build/server/alignset-server" --listen "127.0.0.1:$1" --db "$logs/$2.db" --log-level info \
      "${@:3}" > "$logs/$2.log" 2>&1 &
    server_pid=$!
    sleep 1
  }
  stop() { kill "$server_pid"; wait "$server_pid" || true; }
  timed() {
    local name=$1 port=$2
    shift 2
    local t0
    t0=$(date +%s.%N)
    "$build/cli/alignset" precompute --server "127.0.0.1:$port" "$@" > "$logs/$name.out" 2>&1
    touch "$logs/wall.txt"
    grep -v "^$name " "$logs/wall.txt" > "$logs/wall.tmp" || true
    echo "$name $(echo "$(date +%s.%N) - $t0" | bc)" >> "$logs/wall.tmp"
    mv "$logs/wall.tmp" "$logs/wall.txt"
  }
  box=()
  for a in $(seq 26 34); do for b in $(seq 56 64); do box+=(--key "$a,$b"); done; done
  port=50980
  for row in $rows; do
    port=$((port + 1))
    base=${row%w2}
    flags=()
    [[ $base != "$row" ]] && flags=(--workers 2 --threads-per-worker 1)
    n=${base#one}; n=${n#two}; n=${n#full}; n=${n#shard}; n=${n#whole}
    start "$port" "$row" "${flags[@]}"
    case $base in
      one1024|one4096|whole*) timed "$row" "$port" -n "$n" --space 1dir ;;
      two1024|two4096) timed "$row" "$port" -n "$n" --space keys "${box[@]}" ;;
      full4096) timed "$row" "$port" -n 4096 --space 2dir ;;
      shard4096) timed "$row" "$port" -n 4096 --space 2dir --shard 0/20 ;;
      one*) timed "$row" "$port" -n "$n" --space keys --key 8 --key 7 ;;
      two*) timed "$row" "$port" -n "$n" --space keys --key 31,58 --key 32,58 ;;
    esac
    stop
  done
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
print('2 cores; server defaults (one worker, every core, warm budget 0.13) but in rows marked *2 workers* '
      '(`--workers 2 --threads-per-worker 1`: two keys side by side, each on one core, so a set takes '
      'longer and the seconds per set of those rows are not the wall clock\'s share); a fresh cache per row. '
      'Seconds per set from the server log (`optimize done`), wall clock from the precompute call.\n')
print('| what | wall s | cold sets | median cold s | warm sets | mean warm s | median warm s |')
print('|---|---:|---:|---:|---:|---:|---:|')
rows = {}
names = []
for n in (1024, 4096):
    names += [('one%d' % n, '1 dir, N = %d, the 46 keys' % n),
              ('two%d' % n, '2 dir, N = %d, the 45 keys with phi1 in 26..34, phi2 in 56..64' % n)]
for n in (16384, 65536):
    names += [('one%d' % n, '1 dir, N = %d, the root 8 and its child 7' % n),
              ('two%d' % n, '2 dir, N = %d, the root (31, 58) and its child (32, 58)' % n)]
names += [('shard4096', '2 dir, N = 4096, shard 0/20 of the space (208 keys)'),
          ('full4096', '2 dir, N = 4096, **the whole space, 4141 keys**'),
          ('one4096w2', '1 dir, N = 4096, the 46 keys, *2 workers*'),
          ('shard4096w2', '2 dir, N = 4096, shard 0/20 of the space (208 keys), *2 workers*'),
          ('whole65536', '1 dir, N = 65536, **the 46 keys**'),
          ('whole65536w2', '1 dir, N = 65536, **the 46 keys**, *2 workers*')]
for name, what in names:
    if name not in wall:
        continue
    cold, warm = sets(name)
    rows[name] = (cold, warm)
    med = lambda v: '%.2f' % statistics.median(v) if v else '-'
    mean = lambda v: '%.3f' % statistics.mean(v) if v else '-'
    print('| %s | %.1f | %d | %s | %d | %s | %s |' % (what, float(wall[name]), len(cold), med(cold), len(warm), mean(warm), med(warm)))
print()
if 'full4096' in rows:
    cold, warm = rows['full4096']
    print('Whole two-direction space at N = 4096, measured: %d sets (%d roots, %d warm) in **%.0f s (%.1f min)** '
          'wall clock, %.3f s a set.\n' % (len(cold) + len(warm), len(cold), len(warm), float(wall['full4096']),
                                          float(wall['full4096']) / 60, float(wall['full4096']) / 4141))
# Roots of the lineage (core/align/key_lineage.h, algorithm version 7).
ROOTS_ONE, ROOTS_TWO = 7, 226
for name in ('shard4096', 'shard4096w2'):
    if name in rows:
        cold, warm = rows[name]
        sets_run, seconds = len(cold) + len(warm), float(wall[name])
        print('Whole two-direction space at N = 4096 from shard 0/20%s: %d sets (%d roots) in %.0f s wall, '
              '%.3f s a set: **%.1f min** for 4141 at that rate.\n' % (
                  ', 2 workers' if name.endswith('w2') else '', sets_run, len(cold), seconds,
                  seconds / sets_run, seconds / sets_run * 4141 / 60))
for name in ('whole65536', 'whole65536w2'):
    if name in rows:
        print('N = 65536, the 46 one-direction keys%s, measured: %.0f s wall, **%.1f s a set**.\n' % (
            ', 2 workers' if name.endswith('w2') else '', float(wall[name]), float(wall[name]) / 46))
for name in ('two1024', 'two4096', 'shard4096'):
    if name not in rows or not rows[name][0] or not rows[name][1]:
        continue
    cold, warm = rows[name]
    total = ROOTS_TWO * statistics.median(cold) + (4141 - ROOTS_TWO) * statistics.mean(warm)
    print('Whole two-direction space at N = %s: %d roots x %.2f s + %d x %.3f s = **%.0f s (%.1f min)**.\n' %
          (re.sub(r"^\D+", "", name) + (" (from shard 0/20)" if name == "shard4096" else ""), ROOTS_TWO, statistics.median(cold), 4141 - ROOTS_TWO, statistics.mean(warm), total, total / 60))
for name, keys, roots in [('one16384', 46, ROOTS_ONE), ('two16384', 4141, ROOTS_TWO),
                          ('one65536', 46, ROOTS_ONE), ('two65536', 4141, ROOTS_TWO)]:
    if name in rows and rows[name][0] and rows[name][1]:
        cold, warm = rows[name]
        avg = (roots * statistics.median(cold) + (keys - roots) * statistics.mean(warm)) / keys
        print('N = %s, %d keys: %d roots x %.1f s + %d x %.1f s = %.1f s a set on average over the space.\n' %
              (name[3:], keys, roots, statistics.median(cold), keys - roots, statistics.mean(warm), avg))
EOF
cat "$out/lineage_fill.md"

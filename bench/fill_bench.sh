#!/usr/bin/env bash
# The fill benchmark: how long `alignset precompute` takes to fill the key
# spaces on this machine, through a real server on loopback with a fresh
# cache, for each construction.
#
#   bash bench/fill_bench.sh [OUT.md]          # default bench/results/fill.md
#   CONSTRUCTIONS=lattice SHARDS=40 bash bench/fill_bench.sh /tmp/fill.md
#
# Rows: the 46-key one-direction space at N = 1024 and 4096 (whole); the
# 4141-key two-direction space at 1024 and 4096 sampled as shard 0 of
# SHARDS (every SHARDS-th key of the canonical order for lattices: 208 keys
# for 20, spread over the whole space; a contiguous block of the lineage
# order for optimized keys) and extrapolated to 4141; one key at N = 16384 and
# 65536 (one direction, 30 deg; two directions, 30 and 75 deg). The server
# runs its defaults (one worker with every core) but for SERVER_FLAGS, by
# default --warm-budget 0: every key optimized from Owen-Sobol, the cost
# before the key lineage (algorithm version 5's path; its sets differ from
# version 6's only in the lineage). The lineage's fill times are
# bench/lineage_fill.sh's, whose samples follow the lineage (a sample of
# scattered keys or a lone deep key would count its ancestors too).
# Wall-clock seconds of each precompute call; the machine is shared, so
# compare rows of one run only.
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD_DIR="${BUILD_DIR:-build}"
OUT="${1:-bench/results/fill.md}"
SHARDS="${SHARDS:-20}"
CONSTRUCTIONS="${CONSTRUCTIONS:-optimized lattice}"
cmake --build "$BUILD_DIR" --target alignset-server alignset >/dev/null
WORK=$(mktemp -d)
. scripts/lib/loopback_server.sh
trap 'stop_loopback_server; rm -rf "$WORK"' EXIT
start_loopback_server 30 "$WORK/server.log" "$BUILD_DIR/server/alignset-server" \
  --db "$WORK/fill.sqlite" --log-level warn ${SERVER_FLAGS---warm-budget 0}
CLI="$BUILD_DIR/cli/alignset"

rows=()
run() {  # label keys_in_space keys_run args...
  local label=$1 space_keys=$2 run_keys=$3
  shift 3
  local t0 t1
  t0=$(date +%s.%N)
  "$CLI" precompute --server "$ADDR" "$@" >"$WORK/last.log" 2>&1 || {
    echo "fill_bench: precompute $* failed:" >&2
    tail -5 "$WORK/last.log" >&2
    exit 1
  }
  t1=$(date +%s.%N)
  rows+=("$(/usr/bin/python3 -c "
import sys
label, space, keys, t0, t1 = sys.argv[1], int(sys.argv[2]), int(sys.argv[3]), float(sys.argv[4]), float(sys.argv[5])
s = t1 - t0
per = s / keys
whole = per * space
def hms(x):
    return '%.0f s' % x if x < 120 else ('%.1f min' % (x / 60) if x < 7200 else '%.2f h' % (x / 3600))
print('| %s | %d | %.1f | %.3f | %s |' % (label, keys, s, per, hms(whole)))
" "$label" "$space_keys" "$run_keys" "$t0" "$t1")")
  echo "${rows[-1]}" >&2
}

for c in $CONSTRUCTIONS; do
  two_keys=$(( (4141 + SHARDS - 1) / SHARDS ))
  run "$c, 1 dir, N = 1024 (46 keys)" 46 46 -n 1024 --space 1dir --construction "$c"
  run "$c, 1 dir, N = 4096 (46 keys)" 46 46 -n 4096 --space 1dir --construction "$c"
  run "$c, 2 dir, N = 1024 (shard 0/$SHARDS of 4141)" 4141 "$two_keys" -n 1024 --space 2dir --shard "0/$SHARDS" --construction "$c"
  run "$c, 2 dir, N = 4096 (shard 0/$SHARDS of 4141)" 4141 "$two_keys" -n 4096 --space 2dir --shard "0/$SHARDS" --construction "$c"
  run "$c, 1 dir, N = 16384 (one key, 30°)" 46 1 -n 16384 --space keys --key 30 --construction "$c"
  run "$c, 2 dir, N = 16384 (one key, 30°, 75°)" 4141 1 -n 16384 --space keys --key 30,75 --construction "$c"
  run "$c, 1 dir, N = 65536 (one key, 30°)" 46 1 -n 65536 --space keys --key 30 --construction "$c"
  run "$c, 2 dir, N = 65536 (one key, 30°, 75°)" 4141 1 -n 65536 --space keys --key 30,75 --construction "$c"
done

{
  echo "# Filling the key spaces: \`bash bench/fill_bench.sh\`"
  echo
  echo "$(nproc) cores, load average at the end: $(cut -d' ' -f1-3 /proc/loadavg); server defaults (one worker, every core); a fresh cache; $(date -u +%Y-%m-%d). Wall-clock seconds of one \`alignset precompute\` call per row; *whole space* extrapolates the row's seconds per key to its space (46 or 4141 keys)."
  echo
  echo "| what | keys run | seconds | seconds per key | whole space at this rate |"
  echo "|---|---:|---:|---:|---:|"
  printf '%s\n' "${rows[@]}"
} >"$OUT"
echo "fill_bench: wrote $OUT" >&2

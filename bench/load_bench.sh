#!/usr/bin/env bash
# Cache-hit latency and throughput of alignset-server, measured by a separate
# client process on loopback with 1, 8 and 64 concurrent clients for N = 4096
# and 65536. The cache is pre-populated directly (no optimization runs).
#
#   bench/load_bench.sh [BUILD_DIR] [SECONDS_PER_ROW]
#
# Set CPUS (e.g. CPUS=0,1) to pin server and client to those cores with
# taskset, to reproduce the 2-core figures on a bigger machine.
set -euo pipefail
BUILD=${1:-build}
SECONDS_PER_ROW=${2:-3}
SERVER=$BUILD/server/alignset-server
LOAD=$BUILD/bench/alignset_load_client
for b in "$SERVER" "$LOAD"; do
  [ -x "$b" ] || { echo "load_bench: $b not built (ninja -C $BUILD alignset-server alignset_load_client)" >&2; exit 1; }
done
PIN=()
if [ -n "${CPUS:-}" ]; then PIN=(taskset -c "$CPUS"); fi

WORK=$(mktemp -d /tmp/alignset-load-XXXXXX)
. "$(dirname "$0")/../scripts/lib/loopback_server.sh"
cleanup() {
  stop_loopback_server
  rm -rf "$WORK"
}
trap cleanup EXIT

"$LOAD" populate --db "$WORK/cache.sqlite" --n 4096,65536 --dir 30 --max-iterations 3000 --seed 1 >/dev/null
start_loopback_server 10 "$WORK/server.log" "${PIN[@]}" "$SERVER" --db "$WORK/cache.sqlite" \
  --max-iterations 3000 --seed 1 --log-level warn

echo "# alignset-server cache hits, loopback, $(nproc) cores visible${CPUS:+, pinned to CPUs $CPUS}"
# --dir 120 is served from the canonical phi = 30 set with swap + invert.
"${PIN[@]}" "$LOAD" run --server "$ADDR" --n 4096,65536 --dir 120 --clients 1,8,64 \
  --seconds "$SECONDS_PER_ROW" --warmup 0.5

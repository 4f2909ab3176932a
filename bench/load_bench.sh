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
SERVER_PID=
cleanup() {
  if [ -n "$SERVER_PID" ]; then kill -TERM "$SERVER_PID" 2>/dev/null || true; wait "$SERVER_PID" 2>/dev/null || true; fi
  rm -rf "$WORK"
}
trap cleanup EXIT

"$LOAD" populate --db "$WORK/cache.sqlite" --n 4096,65536 --dir 30 --max-iterations 3000 --seed 1 >/dev/null
"${PIN[@]}" "$SERVER" --listen 127.0.0.1:0 --port-file "$WORK/port" --db "$WORK/cache.sqlite" \
  --max-iterations 3000 --seed 1 --log-level warn &
SERVER_PID=$!
for _ in $(seq 100); do [ -s "$WORK/port" ] && break; sleep 0.1; done
[ -s "$WORK/port" ] || { echo "load_bench: server did not start" >&2; exit 1; }
PORT=$(cat "$WORK/port")

echo "# alignset-server cache hits, loopback, $(nproc) cores visible${CPUS:+, pinned to CPUs $CPUS}"
# --dir 120 is served from the canonical phi = 30 set with swap + invert.
"${PIN[@]}" "$LOAD" run --server "127.0.0.1:$PORT" --n 4096,65536 --dir 120 --clients 1,8,64 \
  --seconds "$SECONDS_PER_ROW" --warmup 0.5

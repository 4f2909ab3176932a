#!/usr/bin/env bash
# The figures of issue 16, taken against one server binary:
#   1. a victim's wait under a greedy client (a precompute of the 4141
#      two-direction keys at N = 32768 running, then 50 more optimizations at
#      N >= 32768 queued by the same connection): latency of new N = 256 sets
#      asked for on a second connection, minus their own optimization time;
#   2. server threads and resident memory with 2,000 GetAlignedSet calls
#      waiting on one connection (all for one N = 65536 key being optimized);
#   3. WatchAlignedSet events per second and the longest silence at N = 65536.
#
#   bench/hardening_bench.sh [BUILD_DIR] [SERVER_BINARY]
#
# SERVER_BINARY defaults to BUILD_DIR/server/alignset-server; pass an older
# build's binary to take the "before" figures (the probe speaks the wire
# contract only). Do not compile while it runs: it times things.
set -euo pipefail
BUILD=${1:-build}
SERVER=${2:-$BUILD/server/alignset-server}
PROBE=$BUILD/bench/alignset_probe_client
for b in "$SERVER" "$PROBE"; do
  [ -x "$b" ] || { echo "hardening_bench: $b not built (ninja -C $BUILD alignset-server alignset_probe_client)" >&2; exit 1; }
done

WORK=$(mktemp -d /tmp/alignset-hardening-XXXXXX)
. "$(dirname "$0")/../scripts/lib/loopback_server.sh"
stop_server() { stop_loopback_server; }
cleanup() { stop_server; rm -rf "$WORK"; }
trap cleanup EXIT

start_server() {  # extra flags...
  rm -f "$WORK"/cache.sqlite*
  start_loopback_server 10 "$WORK/server.log" "$SERVER" --db "$WORK/cache.sqlite" --log-level warn \
    --shutdown-grace 1 "$@"
}

echo "# server: $SERVER"
echo "# $(nproc) cores visible, load average $(cut -d' ' -f1-3 /proc/loadavg)"
echo "## 1. victim under a greedy client (deadline 60 s per victim)"
start_server --workers 1
"$PROBE" greedy --server "$ADDR" --greedy 50 --greedy-n 32768 --precompute-n 32768 --victims "${VICTIMS:-5}" \
  --victim-n 256 --deadline 60
stop_server
echo "## 2. 2,000 waiting calls on one connection"
start_server --workers 1
"$PROBE" waiting --server "$ADDR" --server-pid "$SERVER_PID" --calls 2000 --n 65536 --dir 30
stop_server
echo "## 3. watch events at N = 65536 (20 s)"
start_server --workers 1
"$PROBE" watch --server "$ADDR" --n 65536 --dir 21 --seconds 20
stop_server

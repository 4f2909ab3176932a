#!/usr/bin/env bash
# The main job: installs what it needs, builds the CLI and the server, starts alignset-server
# on its embedded SQLite default, requests an aligned set through the client,
# shows what it got (quality against Owen-scrambled Sobol), asks again to show
# the cache hit, and stops the server cleanly.
#
#   N=4096 THETA=120 scripts/quickstart.sh
set -euo pipefail
cd "$(dirname "$0")/.."
# Only what it runs: the build tools and libraries (no test, benchmark or container tools),
# and only the two programs it uses. A build directory configured here leaves the tests
# and benchmarks out; scripts/test.sh turns them on again.
bash scripts/install-deps.sh
BUILD_DIR="${BUILD_DIR:-build}"
if [ -f "$BUILD_DIR/CMakeCache.txt" ]; then
  TARGETS="alignset alignset-server" bash scripts/build.sh
else
  TARGETS="alignset alignset-server" bash scripts/build.sh \
    -DALIGNSET_BUILD_TESTS=OFF -DALIGNSET_BUILD_BENCH=OFF
fi
N="${N:-1024}"
THETA="${THETA:-30}"
OUT="${OUT:-$BUILD_DIR/quickstart-n$N-theta$THETA.txt}"
SERVER="$BUILD_DIR/server/alignset-server"
CLI="$BUILD_DIR/cli/alignset"

LOG="$BUILD_DIR/quickstart-server.log"
. scripts/lib/loopback_server.sh
trap stop_loopback_server EXIT
: >"$LOG"
start_loopback_server 10 "$LOG" "$SERVER"
echo "alignset-server listening on $ADDR (log: $LOG)"

echo
echo "== request: $N points, spectral direction $THETA deg (edge normal)"
time "$CLI" get --server "$ADDR" --n "$N" --dir "$THETA" --out "$OUT"
echo
echo "== what it achieved"
"$CLI" evaluate "$OUT" --normal "$THETA"
echo
echo "== the same request again (cache hit)"
time "$CLI" get --server "$ADDR" --n "$N" --dir "$THETA" --out "$OUT"
echo
"$CLI" stats --server "$ADDR"

#!/usr/bin/env bash
# A table file for pbrt's "aligned" sampler: aligned lattices for every
# one-direction key on whole and quarter degrees at the given main-sample
# counts, from a fresh alignset-server on loopback (its own cache in a
# temporary folder), exported with `alignset export`.
#
#   integrations/pbrt-v4/make_table.sh OUT.tbl N[,N...] [BUILD_DIR]
#
# The sampler's T samples a pixel are a pre-pass of T/4 and N = 3T/4 main
# samples: 64, 256 and 1024 samples a pixel read N = 48, 192 and 768.
# Two-direction lattices (4141 keys an N) take hours to fill on two cores;
# without them a corner pixel reads its stronger edge's set (docs/pbrt.md).
set -euo pipefail
OUT="${1:?usage: make_table.sh OUT.tbl N[,N...] [BUILD_DIR]}"
NS="${2:?usage: make_table.sh OUT.tbl N[,N...] [BUILD_DIR]}"
ROOT="$(cd "$(dirname "$0")/../.." && pwd)"
BUILD_DIR="${3:-$ROOT/build}"
CLI="$BUILD_DIR/cli/alignset"
SERVER="$BUILD_DIR/server/alignset-server"
[ -x "$CLI" ] && [ -x "$SERVER" ] || { echo "make_table.sh: no $CLI or $SERVER: run scripts/build.sh" >&2; exit 1; }
WORK="$(mktemp -d)"
. "$ROOT/scripts/lib/loopback_server.sh"
trap 'stop_loopback_server; rm -rf "$WORK"' EXIT

start_loopback_server 30 "$WORK/server.log" "$SERVER" --db "$WORK/cache.sqlite" --log-level warn
for step in 1 0.25; do
  "$CLI" precompute --server "$ADDR" --construction lattice -n "$NS" --space 1dir --angle-step "$step" \
    > "$WORK/precompute.log" 2>&1 || { tail -5 "$WORK/precompute.log" >&2; exit 1; }
done
stop_loopback_server
"$CLI" export --db "$WORK/cache.sqlite" -n "$NS" --construction lattice --space 1dir,1dir-quarter -o "$OUT"
echo "make_table.sh: wrote $OUT (lattices, N = $NS, 46 + 181 keys each)"

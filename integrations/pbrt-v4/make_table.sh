#!/usr/bin/env bash
# A table file for pbrt's "aligned" sampler: aligned lattices for every
# one-direction key on whole and quarter degrees at the given main-sample
# counts, searched by `alignset table` (no server: the same core search a
# server runs, the same file `alignset export` writes from its cache).
#
#   integrations/pbrt-v4/make_table.sh OUT.tbl N[,N...] [BUILD_DIR]
#
# The sampler's T samples a pixel are a pre-pass of T/4 and N = 3T/4 main
# samples: 64, 256 and 1024 samples a pixel read N = 48, 192 and 768.
# Two-direction lattices (4141 keys an N) take hours on two cores; without
# them a corner pixel reads its stronger edge's set (docs/pbrt.md).
set -euo pipefail
OUT="${1:?usage: make_table.sh OUT.tbl N[,N...] [BUILD_DIR]}"
NS="${2:?usage: make_table.sh OUT.tbl N[,N...] [BUILD_DIR]}"
ROOT="$(cd "$(dirname "$0")/../.." && pwd)"
BUILD_DIR="${3:-$ROOT/build}"
CLI="$BUILD_DIR/cli/alignset"
[ -x "$CLI" ] || { echo "make_table.sh: no $CLI: run scripts/build.sh" >&2; exit 1; }
"$CLI" table -n "$NS" --construction lattice --space 1dir,1dir-quarter -o "$OUT"
echo "make_table.sh: wrote $OUT (lattices, N = $NS, 46 + 181 keys each)"

#!/usr/bin/env bash
# The main job: installs dependencies, builds, optimizes a direction-aligned
# point set and shows what it achieved against Owen-scrambled Sobol.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
bash scripts/build.sh
BUILD_DIR="${BUILD_DIR:-build}"
N="${N:-1024}"
THETA="${THETA:-30}"
OUT="${OUT:-$BUILD_DIR/aligned-$N-$THETA.txt}"
"$BUILD_DIR/client/alignset" optimize --n "$N" --dir "$THETA" --out "$OUT"
"$BUILD_DIR/client/alignset" evaluate "$OUT" --normal "$THETA"

#!/usr/bin/env bash
# The rendered proof, in one command: builds what it needs, starts its own
# alignset-server on loopback (port 0, --port-file), renders both scenes with
# every sampler at every N (render_bench: fills the one-direction space once
# per N through the client library, with progress), then draws the figures
# and tables (plot_render.py) into bench/results/.
#
#   bash bench/render/run.sh                      # N = 16 ... 4096
#   N=256,1024 SAMPLERS=owen-sobol,aligned bash bench/render/run.sh
#   PREPASS=samples256 bash bench/render/run.sh   # another pre-pass for `aligned`
#   TWO_MAX_N=65536 bash bench/render/run.sh      # two-direction sets at every N (default: up to 2048)
#
# The server's cache lives in $BUILD_DIR/render-cache/ and survives runs: a
# re-run only optimizes what a new algorithm version or profile needs.
set -euo pipefail
cd "$(dirname "$0")/../.."
BUILD_DIR="${BUILD_DIR:-build}"
N="${N:-16,32,64,128,256,512,1024,2048,4096}"
IMAGE_N="${IMAGE_N:-256,1024,4096}"
SAMPLERS="${SAMPLERS:-}"
RAW="${RAW:-$BUILD_DIR/render-results}"
RESULTS="${RESULTS:-bench/results}"
THREADS="${THREADS:-2}"
PREPASS="${PREPASS:-}"
# Two-direction sets up to N = 2048 (the committed figures): the two scenes
# need about 390 two-direction keys per N (the geometry's and the
# estimator's pairs), about 20 minutes per N at N = 2048 on two cores with
# the algorithm-version-3 optimizer, and 40 at 4096. Above, a pixel with two
# edges gets the stronger edge's set. TWO_MAX_N=65536: every N.
TWO_MAX_N="${TWO_MAX_N:-2048}"

. bench/render/render_server.sh
mkdir -p "$RAW"
start_render_server
echo "render: alignset-server on $ADDR (cache $BUILD_DIR/render-cache/cache.sqlite)"

"$BUILD_DIR/bench/render/render_bench" --server "$ADDR" --out "$RAW" --n "$N" \
  --image-n "$IMAGE_N" --threads "$THREADS" ${SAMPLERS:+--samplers "$SAMPLERS"} \
  ${PREPASS:+--prepass "$PREPASS"} ${TWO_MAX_N:+--two-max-n "$TWO_MAX_N"}
/usr/bin/python3 bench/render/plot_render.py --raw "$RAW" --out "$RESULTS" --image-n "$IMAGE_N"

# What the render benchmarks (run.sh, seeds.sh, split.sh) share. Source it
# from the repository root with BUILD_DIR set, then:
#
#   start_render_server
#     builds alignset-server and render_bench, and starts the server on a
#     free loopback port over the benchmarks' shared cache
#     ($BUILD_DIR/render-cache/cache.sqlite, so sets filled by one run serve
#     the next); sets ADDR and stops the server when the script exits.
#   seed_render_bench SEED ARG...
#     render_bench against that server for one scene seed, with only the
#     renders ARG asks for (no line rates, no alternative or compared
#     pre-passes, no extra image N), on THREADS threads (default 2).
#   default_prepass
#     prints the renderer's default pre-pass (kDefaultPrepass in
#     render/spectral_estimator.h).

. scripts/lib/loopback_server.sh

start_render_server() {
  cmake --build "$BUILD_DIR" --target alignset-server render_bench >/dev/null
  mkdir -p "$BUILD_DIR/render-cache"
  trap stop_loopback_server EXIT
  start_loopback_server 30 "$BUILD_DIR/render-cache/server.log" "$BUILD_DIR/server/alignset-server" \
    --db "$BUILD_DIR/render-cache/cache.sqlite" --workers 2 --threads-per-worker 1 --log-level warn
}

seed_render_bench() {
  local seed="$1"
  shift
  "$BUILD_DIR/bench/render/render_bench" --server "$ADDR" --threads "${THREADS:-2}" --seed "$seed" \
    --line-rates 0 --alt-prepass "" --compare-prepass "" --image-n "" "$@"
}

default_prepass() {
  sed -n 's/.*kDefaultPrepass = "\(.*\)";/\1/p' render/spectral_estimator.h
}

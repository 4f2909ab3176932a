#!/usr/bin/env bash
# Runs bench/engine_bench once and prints, per N, the median time per
# iteration (F + gradient) of each engine and the speed-up of the fast
# engine over the direct one, both medians taken from the same run.
#
#   bench/engine_speedup.sh                         # all sizes (~1 min on 2 cores)
#   bench/engine_speedup.sh --benchmark_filter=/4096
#   ENGINE_BENCH=build/bench/engine_bench ALIGNSET_BENCH_THREADS=2 bench/engine_speedup.sh
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
bin="${ENGINE_BENCH:-$root/build/bench/engine_bench}"
if [ ! -x "$bin" ]; then
  echo "engine_speedup: $bin not found; build it with: ninja -C build engine_bench" >&2
  exit 1
fi
json="$(mktemp)"
trap 'rm -f "$json"' EXIT
echo "load before: $(uptime)"
"$bin" --benchmark_format=json --benchmark_out="$json" --benchmark_out_format=json "$@" >/dev/null
echo "load after:  $(uptime)"
/usr/bin/python3 - "$json" <<'PY'
import json, sys
data = json.load(open(sys.argv[1]))
med = {}
for b in data["benchmarks"]:
    if b.get("aggregate_name") != "median" or b.get("error_occurred"):
        continue
    engine, n = b["run_name"].split("/")[1], int(b["run_name"].split("/")[2])
    scale = {"ns": 1e-6, "us": 1e-3, "ms": 1.0, "s": 1e3}[b["time_unit"]]
    med.setdefault(n, {})[engine] = b["real_time"] * scale
ctx = data["context"]
print(f"host: {ctx.get('num_cpus')} cpus, {ctx.get('mhz_per_cpu')} MHz")
print(f"{'N':>7} {'engine':>7} {'median ms/iter':>15} {'speed-up vs direct':>19}")
for n in sorted(med):
    d = med[n].get("direct")
    for engine, t in sorted(med[n].items()):
        ratio = f"{d / t:.1f}x" if d and engine != "direct" else ""
        print(f"{n:>7} {engine:>7} {t:>15.3f} {ratio:>19}")
PY

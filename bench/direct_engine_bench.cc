// The baseline the fast engines are measured against: the direct engine's
// time per optimizer iteration (F over K plus the gradient) at the sizes of
// the supplement's Table 1, and one whole optimization at N = 4096.
//
//   build/bench/direct_engine_bench --benchmark_filter=Iteration
//   build/bench/direct_engine_bench --benchmark_filter=EndToEnd
#include <benchmark/benchmark.h>

#include "core/spectral/direct_engine.h"
#include "core/spectral/frequency_set.h"
#include "core/optimize/optimizer.h"
#include "core/sampling/owen_sobol.h"

namespace alignset {
namespace {

constexpr int kThreads = 2;

void BM_DirectIteration(benchmark::State& state) {
  const uint32_t n = static_cast<uint32_t>(state.range(0));
  DirectEngine engine(kThreads);
  const auto k = BuildFrequencySet(DefaultFrequencyParams(n), AnisotropyDirections({30}));
  engine.SetFrequencies(k);
  const PointSet pts = OwenScrambledSobol(n, 1);
  SpectrumEvaluation out;
  for (auto _ : state) {
    engine.Evaluate(pts, true, &out);
    benchmark::DoNotOptimize(out.loss);
  }
  state.counters["K"] = static_cast<double>(k.size());
  state.counters["pairs_per_s"] = benchmark::Counter(
      2.0 * n * static_cast<double>(k.size()), benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK(BM_DirectIteration)->Arg(4096)->Arg(16384)->Unit(benchmark::kMillisecond)->UseRealTime()
    ->Repetitions(5)->ReportAggregatesOnly(true);
BENCHMARK(BM_DirectIteration)->Arg(65536)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(1)
    ->Repetitions(3)->ReportAggregatesOnly(true);

void BM_DirectEndToEnd(benchmark::State& state) {
  const uint32_t n = static_cast<uint32_t>(state.range(0));
  OptimizationProblem problem;
  problem.n = n;
  problem.directions = {30};
  OptimizerOptions options;
  int iterations = 0;
  for (auto _ : state) {
    DirectEngine engine(kThreads);
    auto r = Optimize(problem, options, engine);
    if (!r.ok()) {
      state.SkipWithError(r.status().ToString().c_str());
      return;
    }
    iterations = r->iterations;
    benchmark::DoNotOptimize(r->final_loss.total);
  }
  state.counters["iterations"] = iterations;
}
BENCHMARK(BM_DirectEndToEnd)->Arg(4096)->Unit(benchmark::kSecond)->UseRealTime()->Iterations(1);

}  // namespace
}  // namespace alignset

BENCHMARK_MAIN();

// Per-iteration cost (F over K plus the gradient) of the spectral engines on
// the sets the optimizer evaluates: 3-direction sets (theta = 30 degrees),
// default frequency parameters, Owen-scrambled Sobol points.
//
//   build/bench/engine_bench --benchmark_filter='fast'      # fast engine only
//   bench/engine_speedup.sh                                 # ratios, one run
//
// Threads: 2, or ALIGNSET_BENCH_THREADS. Direct at N = 65536 takes seconds
// per iteration, so it runs once per repetition and 3 repetitions; the
// reported figure is the median over repetitions.
#include <benchmark/benchmark.h>

#include <cstdlib>
#include <memory>
#include <string>

#include "core/spectral/direct_engine.h"
#include "core/spectral/fast_engine.h"
#include "core/spectral/frequency_set.h"
#include "core/sampling/owen_sobol.h"
#ifdef ALIGNSET_HAVE_CUDA
#include "core/spectral/cuda/cuda_engine.h"
#endif

namespace alignset {
namespace {

int BenchThreads() {
  const char* env = std::getenv("ALIGNSET_BENCH_THREADS");
  const int t = env ? std::atoi(env) : 0;
  return t > 0 ? t : 2;
}

std::unique_ptr<SpectralEngine> MakeEngine(const std::string& kind) {
  if (kind == "direct") return std::make_unique<DirectEngine>(BenchThreads());
  if (kind == "fast") return std::make_unique<FastEngine>(BenchThreads());
  auto engine = MakeSpectralEngine(EngineKind::kCuda, BenchThreads());
  return engine.ok() ? std::move(engine).value() : nullptr;
}

void EngineIteration(benchmark::State& state, const std::string& kind) {
  const uint32_t n = static_cast<uint32_t>(state.range(0));
  std::unique_ptr<SpectralEngine> engine = MakeEngine(kind);
  if (!engine) {
    state.SkipWithError("engine not available here");
    return;
  }
  const std::vector<Frequency> k =
      BuildFrequencySet(DefaultFrequencyParams(n), AnisotropyDirections({30.0}));
  const PointSet points = OwenScrambledSobol(n, 1);
  engine->SetFrequencies(k);
  SpectrumEvaluation out;
  engine->Evaluate(points, true, &out);  // warm: first-touch of buffers
  for (auto _ : state) {
    engine->Evaluate(points, true, &out);
    benchmark::DoNotOptimize(out.loss);
  }
  state.counters["N"] = n;
  state.counters["K"] = static_cast<double>(k.size());
  state.counters["threads"] = BenchThreads();
}

// What a time slice costs the fast engine when the scheduler resumes a
// paused optimization after another one ran on the engine: binding K again
// (the resumed run's state is kept, so nothing else is recomputed).
void SwitchFrequencies(benchmark::State& state) {
  const uint32_t n = static_cast<uint32_t>(state.range(0));
  FastEngine engine(BenchThreads());
  const std::vector<Frequency> a =
      BuildFrequencySet(DefaultFrequencyParams(n), AnisotropyDirections({30.0}));
  const std::vector<Frequency> b =
      BuildFrequencySet(DefaultFrequencyParams(n), AnisotropyDirections({12.0, 100.0}));
  bool flip = false;
  for (auto _ : state) {
    engine.SetFrequencies(flip ? a : b);
    flip = !flip;
  }
  state.counters["N"] = n;
}

void Register() {
  for (int n : {4096, 65536}) {
    benchmark::RegisterBenchmark("engine/fast_switch_k", SwitchFrequencies)
        ->Arg(n)
        ->UseRealTime()
        ->Unit(benchmark::kMillisecond)
        ->Repetitions(5)
        ->ReportAggregatesOnly(true);
  }
  for (int n : {4096, 16384, 65536}) {
    auto* direct = benchmark::RegisterBenchmark("engine/direct", EngineIteration, "direct");
    direct->Arg(n)->UseRealTime()->Unit(benchmark::kMillisecond)->ReportAggregatesOnly(true);
    if (n >= 65536) {
      direct->Iterations(1)->Repetitions(3);
    } else {
      direct->Repetitions(5);
    }
    benchmark::RegisterBenchmark("engine/fast", EngineIteration, "fast")
        ->Arg(n)
        ->UseRealTime()
        ->Unit(benchmark::kMillisecond)
        ->Repetitions(9)
        ->ReportAggregatesOnly(true);
#ifdef ALIGNSET_HAVE_CUDA
    benchmark::RegisterBenchmark("engine/cuda", EngineIteration, "cuda")
        ->Arg(n)
        ->UseRealTime()
        ->Unit(benchmark::kMillisecond)
        ->Repetitions(5)
        ->ReportAggregatesOnly(true);
#endif
  }
}

}  // namespace
}  // namespace alignset

int main(int argc, char** argv) {
  alignset::Register();
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}

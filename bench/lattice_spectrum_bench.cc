// What the aligned lattice's generator search costs, and what tabulating
// the polygon coefficients (core/analysis/integer_indicator_spectrum.h)
// saves against the direct coefficients (lattice_variance.h's
// IndicatorSpectrum) on the same sums: the final stage's work for one
// generator, the energies of the scored edges (one direction, 37 degrees,
// 9 normals x 3 offsets) at every dual point within N / 2, and the whole
// choice.
//
//   build/bench/lattice_spectrum_bench --benchmark_repetitions=5
//       --benchmark_report_aggregates_only=true   (one command line)
#include <benchmark/benchmark.h>

#include <vector>

#include "core/analysis/convex_polygon.h"
#include "core/analysis/integer_indicator_spectrum.h"
#include "core/analysis/lattice_variance.h"
#include "core/optimize/aligned_lattice.h"
#include "core/sampling/rank1_lattice.h"
#include "core/util/angles.h"

namespace alignset {
namespace {

std::vector<Polygon> Edges() {
  std::vector<Polygon> out;
  for (int k = -4; k <= 4; ++k) {
    const Vec2 n = UnitVector(37.0 + 0.25 * k);
    for (double offset : {0.0, 0.21, -0.33}) {
      out.push_back(ClipHalfPlane(UnitSquarePolygon(), n, 0.5 * (n.x + n.y) + offset));
    }
  }
  return out;
}

template <class Spectrum>
void DualSum(benchmark::State& state, const std::vector<Spectrum>& edges, uint32_t n) {
  const std::vector<Frequency> dual = Rank1DualHalfDisk(n, Rank1Generator(n), static_cast<int>(n / 2));
  for (auto _ : state) {
    double sum = 0.0;
    for (const Frequency& h : dual) {
      for (const Spectrum& e : edges) sum += e.Energy(h.a, h.b);
    }
    benchmark::DoNotOptimize(sum);
  }
  state.counters["dual_points"] = static_cast<double>(dual.size());
}

void BM_DualSumDirect(benchmark::State& state) {
  const uint32_t n = static_cast<uint32_t>(state.range(0));
  std::vector<IndicatorSpectrum> edges;
  for (const Polygon& p : Edges()) edges.emplace_back(p);
  DualSum(state, edges, n);
}

void BM_DualSumTabulated(benchmark::State& state) {
  const uint32_t n = static_cast<uint32_t>(state.range(0));
  std::vector<IntegerIndicatorSpectrum> edges;
  for (const Polygon& p : Edges()) edges.emplace_back(p, static_cast<int>(n / 2));
  DualSum(state, edges, n);
}

void BM_Tables(benchmark::State& state) {
  const int radius = static_cast<int>(state.range(0) / 2);
  const std::vector<Polygon> polygons = Edges();
  for (auto _ : state) {
    std::vector<IntegerIndicatorSpectrum> edges;
    for (const Polygon& p : polygons) edges.emplace_back(p, radius);
    benchmark::DoNotOptimize(edges.data());
  }
}

void BM_ChooseGenerator(benchmark::State& state) {
  const uint32_t n = static_cast<uint32_t>(state.range(0));
  std::vector<double> dirs = {37.0};
  if (state.range(1) == 2) dirs.push_back(101.0);
  AlignedLatticeOptions o;
  o.threads = 1;
  for (auto _ : state) benchmark::DoNotOptimize(ChooseAlignedLatticeGenerator(n, dirs, o));
}

BENCHMARK(BM_DualSumDirect)->Arg(1024)->Arg(4096)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_DualSumTabulated)->Arg(1024)->Arg(4096)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Tables)->Arg(1024)->Arg(4096)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ChooseGenerator)->Args({256, 1})->Args({1024, 1})->Args({1024, 2})->Args({4096, 1})
    ->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace alignset

BENCHMARK_MAIN();

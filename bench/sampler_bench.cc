// What the sampler library costs a renderer: the bookkeeping per pixel (the
// pre-pass points, the plan from a 3 x 3 or 5 x 5 block of pre-pass values,
// the main points and the estimate: everything but the integrand's
// evaluations) at N = 256, 1024 and 4096, on one thread and on two; the
// table file's size for every space, construction and N; and its load time;
// the joint lattice's cost a value, direct and through a pixel's view.
//
//   build/bench/sampler_bench                        # sizes, then every benchmark
//   build/bench/sampler_bench --benchmark_filter=Pixel
//   build/bench/sampler_bench --benchmark_filter=JointLattice
//
// allocs/pixel counts the allocations of the whole process while a pixel's
// calls run, after a warm-up pass over the image with the thread's Scratch.
//
// The tables hold arbitrary valid generators and Owen-Sobol point sets:
// neither the bookkeeping nor a load depends on which lattice or set a key
// holds. The pixels are a straight edge's (a direction found, a set read)
// and a smooth gradient's (none found, the Owen-Sobol fallback), half each.
#include <alignset/aligned_sampler.h>
#include <alignset/joint_lattice.h>
#include <alignset/set_table.h>
#include <benchmark/benchmark.h>

#include <atomic>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <new>
#include <numeric>
#include <vector>

// Every allocation of the process, counted: the allocations a pixel makes.
static std::atomic<uint64_t> g_allocations{0};
void* operator new(std::size_t size) {
  g_allocations.fetch_add(1, std::memory_order_relaxed);
  if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
  throw std::bad_alloc();
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }

#include "core/sampling/owen_sobol.h"

namespace alignset {
namespace {

TableSection Lattices(uint32_t n, TableSpace space) {
  TableSection s;
  s.n = n;
  s.construction = "lattice";
  s.space = space;
  for (uint32_t k = 0; k < TableSpaceKeys(space); ++k) {
    uint32_t g = 1 + (2 * k + 1) % (n - 1);
    while (std::gcd(g, n) != 1) ++g;
    s.generators.push_back(g);
  }
  return s;
}

TableSection Points(uint32_t n, TableSpace space) {
  TableSection s;
  s.n = n;
  s.construction = "optimized";
  s.space = space;
  for (uint32_t k = 0; k < TableSpaceKeys(space); ++k) s.sets.push_back(OwenScrambledSobol(n, k));
  return s;
}

// The file's size: header, directory, payload, checksum (the format, checked
// against Serialize for every table small enough to build here).
uint64_t FileBytes(uint32_t n, TableSpace space, bool lattice) {
  const uint64_t keys = TableSpaceKeys(space);
  return 16 + 20 + (lattice ? 4 * keys : 16 * keys * n) + 4;
}

void PrintSizes() {
  std::printf("table file sizes (one section each)\n%-8s %-13s %-8s %14s\n", "N", "space", "construction", "bytes");
  for (uint32_t n : {256u, 1024u, 4096u}) {
    for (TableSpace space : {TableSpace::kOneDirection, TableSpace::kOneQuarter, TableSpace::kTwoDirections}) {
      for (bool lattice : {true, false}) {
        const uint64_t bytes = FileBytes(n, space, lattice);
        if (lattice || space != TableSpace::kTwoDirections || n <= 256) {
          auto t = SetTable::FromSections({lattice ? Lattices(n, space) : Points(n, space)});
          if (!t.ok() || (*t)->Serialize().size() != bytes) std::printf("size mismatch N=%u\n", n);
        }
        std::printf("%-8u %-13s %-8s %14llu\n", n, TableSpaceName(space),
                    lattice ? "lattice, tent-lattice" : "optimized, net", static_cast<unsigned long long>(bytes));
      }
    }
  }
  std::fflush(stdout);
}

// A 16 x 16 image's pre-pass values: left half an edge at 37 degrees through
// each pixel, right half a smooth gradient.
struct Frame {
  AlignedSampler sampler;
  uint32_t width = 16;
  std::vector<std::vector<double>> pre;
  static Frame Make(uint32_t n) {
    auto table = SetTable::FromSections({Lattices(n, TableSpace::kOneDirection), Lattices(n, TableSpace::kTwoDirections)});
    AlignedSamplerOptions o;
    o.n = n;
    o.image_width = 16;
    Frame f{*AlignedSampler::Create(*table, o)};
    f.pre.assign(16 * 16, {});
    std::vector<Point2> pts(f.sampler.prepass_samples());
    for (uint32_t y = 0; y < 16; ++y) {
      for (uint32_t x = 0; x < 16; ++x) {
        f.sampler.PrepassPoints(x, y, pts);
        for (const Point2& p : pts) f.pre[y * 16 + x].push_back(Value(x, y, p));
      }
    }
    return f;
  }
  static double Value(uint32_t x, uint32_t y, Point2 p) {
    if (x >= 8) return 0.1 * (x + p.x) + 0.05 * (y + p.y);
    return std::cos(0.6458) * (p.x - 0.5) + std::sin(0.6458) * (p.y - 0.5) > 0.0 ? 1.0 : 0.0;
  }
};

void BM_PixelBookkeeping(benchmark::State& state) {
  static Frame frames[3] = {Frame::Make(256), Frame::Make(1024), Frame::Make(4096)};
  const Frame& f = frames[state.range(0) == 256 ? 0 : state.range(0) == 1024 ? 1 : 2];
  const AlignedSampler& s = f.sampler;
  AlignedSampler::Scratch scratch;
  std::vector<Point2> pre(s.prepass_samples()), main(s.n());
  std::vector<double> values(s.n(), 0.5);
  std::vector<std::span<const double>> block(9);
  auto pixel = [&](uint32_t i) {
    const uint32_t x = 1 + i % 14, y = 1 + (i / 14) % 14;
    s.PrepassPoints(x, y, pre);
    for (int k = 0; k < 9; ++k) block[k] = f.pre[(y + k / 3 - 1) * 16 + (x + k % 3 - 1)];
    auto plan = s.Plan(x, y, block, scratch);
    s.MainPoints(*plan, main);
    benchmark::DoNotOptimize(s.Estimate(*plan, f.pre[y * 16 + x], values));
    benchmark::DoNotOptimize(main.data());
  };
  // A thread's Scratch grows over its first pixels; a renderer keeps it for
  // the whole image, so the warm-up is not what a pixel costs.
  for (uint32_t k = 0; k < 196; ++k) pixel(k);
  uint32_t i = static_cast<uint32_t>(state.thread_index()) * 37;
  const uint64_t allocations_before = g_allocations.load();
  for (auto _ : state) pixel(i++);
  state.SetItemsProcessed(state.iterations());
  // The process's count is shared: read on one thread only.
  if (state.threads() == 1) {
    state.counters["allocs/pixel"] =
        static_cast<double>(g_allocations.load() - allocations_before) / static_cast<double>(state.iterations());
  }
  state.counters["pixels/s"] = benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_PixelBookkeeping)->Arg(256)->Arg(1024)->Arg(4096)->Threads(1)->Threads(2)->UseRealTime();

// The joint lattice's values as pbrt asks for them: a pixel's wave of 64
// samples in a row, each sample's first 40 dimensions (pbrt's nine in the
// lattice, the wavelength folded, the rest padded: a path of a few
// bounces), through JointLattice::Sample (every value hashes its shift or
// scramble) or a JointLatticePixel (the pixel's hashes made once). A value's
// cost is the time over items.
void BM_JointLatticeValues(benchmark::State& state) {
  const uint32_t n = static_cast<uint32_t>(state.range(0));
  const bool view = state.range(1) != 0;
  const auto lattice = JointLattice::Create(n, 9, 3, {1, 1, 1, 1, 4});
  constexpr uint32_t kWave = 64, kDimensions = 40;
  JointLatticePixel pixel_view;
  uint64_t pixel = 0;
  uint32_t wave_start = 0;
  double sum = 0.0;
  for (auto _ : state) {
    if (view) pixel_view.Reset(*lattice, pixel);
    for (uint32_t i = wave_start; i < wave_start + kWave; ++i) {
      for (uint32_t d = 0; d < kDimensions; ++d) sum += view ? pixel_view.Sample(i, d) : lattice->Sample(pixel, i, d);
    }
    if (++pixel == 160 * 160) {
      pixel = 0;
      wave_start = (wave_start + kWave) % n;
    }
  }
  benchmark::DoNotOptimize(sum);
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations()) * kWave * kDimensions);
}
BENCHMARK(BM_JointLatticeValues)->ArgNames({"N", "view"})->ArgsProduct({{256, 1024}, {0, 1}});

void BM_TableLoad(benchmark::State& state) {
  const uint32_t n = static_cast<uint32_t>(state.range(0));
  const TableSpace space = static_cast<TableSpace>(state.range(1));
  const bool lattice = state.range(2) != 0;
  const std::vector<uint8_t> bytes =
      (*SetTable::FromSections({lattice ? Lattices(n, space) : Points(n, space)}))->Serialize();
  for (auto _ : state) benchmark::DoNotOptimize(SetTable::Parse(bytes));
  state.SetBytesProcessed(static_cast<int64_t>(state.iterations() * bytes.size()));
}
BENCHMARK(BM_TableLoad)
    ->Args({256, 1, 1})->Args({4096, 3, 1})->Args({4096, 1, 0})->Args({4096, 2, 0})->Args({256, 3, 0})
    ->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace alignset

int main(int argc, char** argv) {
  alignset::PrintSizes();
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}

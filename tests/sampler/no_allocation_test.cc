// The hot path allocates nothing: once a thread's Scratch has grown (on its
// first pixel), every later pixel's pre-pass points, plan, main points and
// estimate run without a single allocation, on frames with other seeds
// (other points, other crossings) too. Counted by replacing the global
// operator new in this test binary.
#include <alignset/aligned_sampler.h>
#include <alignset/joint_lattice.h>

#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <cstdlib>
#include <new>
#include <string>
#include <vector>

#include "tests/sampler/table_fixture.h"

namespace {
std::atomic<uint64_t> g_allocations{0};
}  // namespace

void* operator new(std::size_t size) {
  g_allocations.fetch_add(1, std::memory_order_relaxed);
  if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
  throw std::bad_alloc();
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }

namespace alignset {
namespace {

// A 14 x 14 image: a corner of two edges on the left half, a smooth
// gradient on the right, so that pixels with one, two and no direction all
// occur; on a shared domain, the corner moves a little from pixel to pixel.
double Value(uint32_t x, uint32_t y, Point2 p, bool shared) {
  const double u = shared ? p.x : x + p.x, v = shared ? p.y : y + p.y;
  if (x >= 7) return 0.1 * u + 0.05 * v;
  const double c = shared ? 0.5 + 0.02 * x : 7.0;
  return (0.8 * (u - c) + 0.6 * (v - (shared ? 0.5 : 6.5)) > 0.0 && u - 0.3 * v < c + 0.2) ? 1.0 : 0.0;
}

// One frame through the recipe with `scratch`; returns the allocations made.
uint64_t Frame(const AlignedSampler& s, bool shared, AlignedSampler::Scratch& scratch) {
  constexpr uint32_t kW = 14;
  const uint32_t m = s.prepass_samples();
  const int r = s.block_radius(), side = s.block_side();
  std::vector<std::vector<double>> pre(kW * kW);
  std::vector<Point2> pts(std::max(m, s.n()));
  for (uint32_t y = 0; y < kW; ++y) {
    for (uint32_t x = 0; x < kW; ++x) {
      s.PrepassPoints(x, y, std::span(pts).first(m));
      for (uint32_t j = 0; j < m; ++j) pre[y * kW + x].push_back(Value(x, y, pts[j], shared));
    }
  }
  std::vector<std::span<const double>> block(static_cast<size_t>(side * side));
  std::vector<double> main(s.n());
  volatile double sink = 0.0;
  const uint64_t before = g_allocations.load();
  for (uint32_t y = 0; y < kW; ++y) {
    for (uint32_t x = 0; x < kW; ++x) {
      for (int k = 0; k < side * side; ++k) {
        const int bx = static_cast<int>(x) + k % side - r, by = static_cast<int>(y) + k / side - r;
        block[k] = bx >= 0 && by >= 0 && bx < static_cast<int>(kW) && by < static_cast<int>(kW)
                       ? std::span<const double>(pre[by * kW + bx])
                       : std::span<const double>();
      }
      s.PrepassPoints(x, y, std::span(pts).first(m));
      auto plan = s.Plan(x, y, block, scratch);
      if (!plan.ok()) return ~uint64_t{0};
      s.MainPoints(*plan, std::span(pts).first(s.n()));
      for (uint32_t i = 0; i < s.n(); ++i) main[i] = Value(x, y, pts[i], shared);
      sink = sink + s.Estimate(*plan, pre[y * kW + x], main);
    }
  }
  return g_allocations.load() - before;
}

// The table a construction's sampler reads: lattices as generators, the
// lattice sequence and the optimized sets as points (each its own section:
// the lookup is by construction).
TableSection SectionOf(const std::string& construction, TableSpace space) {
  if (construction == "lattice" || construction == "tent-lattice") {
    return testing::LatticeSection(256, space, construction == "tent-lattice");
  }
  TableSection s = testing::PointsSection(256, space);
  s.construction = construction;
  return s;
}

// A first frame grows the thread's buffers; the frames after it (other
// seeds: other points, other crossings) allocate nothing.
void ExpectNoAllocationsAfterWarmUp(AlignedSamplerOptions o, bool shared,
                                    TableSpace space = TableSpace::kOneDirection) {
  auto table = SetTable::FromSections({SectionOf(o.construction, space)});
  ASSERT_TRUE(table.ok());
  AlignedSampler::Scratch scratch;
  o.seed = 1;
  const uint64_t first = Frame(*AlignedSampler::Create(*table, o), shared, scratch);
  EXPECT_GT(first, 0u);  // the counter counts
  for (uint64_t seed : {2, 3, 4}) {
    o.seed = seed;
    const AlignedSampler s = *AlignedSampler::Create(*table, o);
    const uint64_t with_direction = scratch.stats().with_direction;
    EXPECT_EQ(Frame(s, shared, scratch), 0u) << "allocations in frame " << seed << " (196 pixels)";
    EXPECT_GT(scratch.stats().with_direction, with_direction);  // edges were fitted
  }
}

TEST(SamplerHotPath, NoAllocationPerPixelOnFootprints) {
  AlignedSamplerOptions o;
  o.n = 256;
  o.image_width = 14;
  ExpectNoAllocationsAfterWarmUp(o, false);
}

// Every construction a table can hold, each a table of its own: the section
// is resolved at Create and a point set's alignments made there, so its
// first frame's pixels allocate no more than a lattice's (the scratch) and
// the later frames nothing. Nets are stored as points like the optimized
// sets, so the points path covers them.
TEST(SamplerHotPath, NoAllocationPerPixelForEveryConstruction) {
  for (const char* c : {"lattice", "tent-lattice", "lattice-sequence", "optimized", "net"}) {
    for (TableSpace space : {TableSpace::kOneDirection, TableSpace::kOneQuarter}) {
      SCOPED_TRACE(std::string(c) + " " + TableSpaceName(space));
      AlignedSamplerOptions o;
      o.n = 256;
      o.image_width = 14;
      o.construction = c;
      ExpectNoAllocationsAfterWarmUp(o, false, space);
    }
  }
}

// The first frame of a point set's sampler allocates what a lattice's does:
// nothing per set, however many directions its pixels read.
TEST(SamplerHotPath, APointSetsFirstFrameAllocatesNoMoreThanALatticesDoes) {
  auto first_frame = [](const std::string& construction) {
    auto table = SetTable::FromSections({SectionOf(construction, TableSpace::kOneDirection)});
    EXPECT_TRUE(table.ok());
    AlignedSamplerOptions o;
    o.n = 256;
    o.image_width = 14;
    o.construction = construction;
    auto s = AlignedSampler::Create(*table, o);
    EXPECT_TRUE(s.ok());
    AlignedSampler::Scratch scratch;
    return Frame(*s, false, scratch);
  };
  first_frame("lattice");  // the process's one-time tables (the served directions' alignments)
  const uint64_t lattice = first_frame("lattice");
  EXPECT_EQ(first_frame("lattice-sequence"), lattice);
  EXPECT_EQ(first_frame("optimized"), lattice);
}

TEST(SamplerHotPath, NoAllocationPerPixelOnASharedDomain) {
  AlignedSamplerOptions o;
  o.n = 256;
  o.image_width = 14;
  o.domain = PixelDomain::kShared;
  ExpectNoAllocationsAfterWarmUp(o, true);
}

TEST(SamplerHotPath, TheJointLatticeAllocatesNothingAfterCreate) {
  // pbrt's nine dimensions and a folded wavelength, at a lattice that keeps
  // all nine (256) and one that pads past four (16): whole frames of every
  // sample's every dimension, padding included; shifted, shifted then
  // folded by the tent, and jittered.
  for (int randomize = 0; randomize < 3; ++randomize) {
    const std::vector<bool> tents = randomize == 1 ? std::vector<bool>{true, true, true, true, false, true}
                                                   : std::vector<bool>{};
    for (uint32_t n : {16u, 256u}) {
      auto l = JointLattice::Create(n, 9, 5, {1, 1, 1, 1, 4}, tents, randomize == 2);
      ASSERT_TRUE(l.ok());
      volatile double sink = 0.0;
      const uint64_t before = g_allocations.load();
      JointLatticePixel view;  // and the per-pixel view a renderer keeps per thread
      for (uint64_t pixel = 0; pixel < 64 * 64; ++pixel) {
        view.Reset(*l, pixel);
        for (uint32_t i = 0; i < n; ++i) {
          for (uint32_t d = 0; d < 24; ++d) sink = sink + l->Sample(pixel, i, d) + view.Sample(i, d);
        }
      }
      EXPECT_EQ(g_allocations.load() - before, 0u) << "N=" << n << ", randomization " << randomize;
    }
  }
}

}  // namespace
}  // namespace alignset

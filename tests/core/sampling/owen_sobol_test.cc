#include "core/sampling/owen_sobol.h"

#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <vector>

#include "tests/net_intervals.h"

namespace alignset {
namespace {

void ExpectNet(const PointSet& pts, int m) {
  ASSERT_EQ(pts.size(), size_t{1} << m);
  EXPECT_EQ(testing::NetViolation(pts), "");
}

TEST(OwenSobol, EveryPowerOfTwoIsANetForSeveralSeeds) {
  for (uint64_t seed : {0ull, 1ull, 42ull, 0xdeadbeefull}) {
    for (int m = 2; m <= 12; ++m) ExpectNet(OwenScrambledSobol(1u << m, seed), m);
  }
}

TEST(OwenSobol, EveryAlignedBlockOfAPowerOfTwoIsANet) {
  // Points [k 2^m, (k + 1) 2^m) of the shuffled sequence: the renderer
  // weights such blocks as nets of their own (render/prepass_reuse.h).
  for (uint64_t seed : {3ull, 77ull}) {
    const PointSet all = OwenScrambledSobol(4096, seed);
    for (int m = 2; m <= 10; m += 2) {
      for (uint32_t k : {1u, 2u, 3u, 4096u / (1u << m) - 1}) {
        ExpectNet(PointSet(all.begin() + k * (1u << m), all.begin() + (k + 1) * (1u << m)), m);
      }
    }
  }
}

TEST(OwenSobol, UnscrambledDimensionsAreANet) {
  for (int m = 2; m <= 10; ++m) {
    PointSet pts;
    for (uint32_t i = 0; i < (1u << m); ++i) {
      pts.push_back({SobolDim0(i) * 0x1.0p-32, SobolDim1(i) * 0x1.0p-32});
    }
    ExpectNet(pts, m);
  }
}

TEST(OwenSobol, DeterministicPerSeedAndDifferentAcrossSeeds) {
  EXPECT_EQ(OwenScrambledSobol(1000, 7), OwenScrambledSobol(1000, 7));
  EXPECT_NE(OwenScrambledSobol(1000, 7), OwenScrambledSobol(1000, 8));
}

TEST(OwenSobol, AnyCountGivesDistinctPointsInTheUnitSquare) {
  for (uint32_t n : {1u, 3u, 17u, 100u, 1000u, 3000u}) {
    const PointSet pts = OwenScrambledSobol(n, 3);
    ASSERT_EQ(pts.size(), n);
    std::set<std::pair<double, double>> seen;
    for (const Point2& p : pts) {
      EXPECT_GE(p.x, 0.0);
      EXPECT_LT(p.x, 1.0);
      EXPECT_GE(p.y, 0.0);
      EXPECT_LT(p.y, 1.0);
      seen.insert({p.x, p.y});
    }
    EXPECT_EQ(seen.size(), n);
  }
}

TEST(OwenSobol, NonPowerOfTwoPrefixIsStratifiedInRows) {
  // The first N points of a shuffled net: each row of height 1/2^floor(log2 N)
  // holds at most two points.
  const uint32_t n = 1500;
  const PointSet pts = OwenScrambledSobol(n, 11);
  std::vector<int> rows(1024, 0);
  for (const Point2& p : pts) ++rows[static_cast<int>(p.y * 1024)];
  for (int c : rows) EXPECT_LE(c, 2);
}

}  // namespace
}  // namespace alignset

#include "core/sampling/samplers.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <set>
#include <string>
#include <vector>

#include "core/sampling/owen_sobol.h"
#include "core/sampling/poisson_disk.h"
#include "core/sampling/rank1_lattice.h"
#include "core/sampling/sampler_radical_inverse.h"
#include "core/sampling/sampler_stratified.h"
#include "core/sampling/sampler_util.h"
#include "tests/unit_square.h"

namespace alignset {
namespace {

PointSet Make(const std::string& name, uint32_t n, uint64_t seed = 1) {
  auto s = Sample(name, n, seed);
  EXPECT_TRUE(s.ok()) << name << " " << n << ": " << s.status().message();
  return s.ok() ? *s : PointSet{};
}

uint32_t Bin(double v, uint32_t cells) { return static_cast<uint32_t>(std::floor(v * cells)); }

// Every cell of a cols x rows grid holds exactly `per_cell` points.
::testing::AssertionResult EvenlyStratified(const PointSet& p, uint32_t cols, uint32_t rows,
                                            int per_cell = 1) {
  std::vector<int> count(static_cast<size_t>(cols) * rows, 0);
  for (const Point2& q : p) {
    const uint32_t i = Bin(q.x, cols), j = Bin(q.y, rows);
    if (i >= cols || j >= rows) return ::testing::AssertionFailure() << "point outside [0,1)";
    ++count[static_cast<size_t>(j) * cols + i];
  }
  for (size_t c = 0; c < count.size(); ++c) {
    if (count[c] != per_cell) {
      return ::testing::AssertionFailure()
             << "cell " << c % cols << "," << c / cols << " of " << cols << "x" << rows
             << " holds " << count[c] << " points, expected " << per_cell;
    }
  }
  return ::testing::AssertionSuccess();
}

// (0,m,2)-net in base 2: every elementary interval of area 2^-m, of every
// shape 2^-a x 2^-(m-a), holds exactly one point.
::testing::AssertionResult IsNet(const PointSet& p) {
  const int m = static_cast<int>(std::log2(static_cast<double>(p.size())));
  if ((size_t{1} << m) != p.size()) return ::testing::AssertionFailure() << "not a power of two";
  for (int a = 0; a <= m; ++a) {
    auto r = EvenlyStratified(p, 1u << a, 1u << (m - a));
    if (!r) return r << " (prefix " << p.size() << ", shape " << a << ")";
  }
  return ::testing::AssertionSuccess();
}

TEST(SamplerRegistry, EverySamplerMakesNPointsInTheSquareDeterministically) {
  const std::set<std::string> seedless = {"grid", "halton", "hammersley", "sobol"};
  for (const std::string& name : SamplerNames()) {
    const PointSet a = Make(name, 256, 5);
    ASSERT_EQ(a.size(), 256u) << name;
    ASSERT_EQ(testing::OutsideUnitSquare(a), "") << name;
    EXPECT_EQ(Make(name, 256, 5), a) << name << " is not deterministic";
    if (seedless.count(name)) {
      EXPECT_EQ(Make(name, 256, 6), a) << name;
    } else {
      EXPECT_NE(Make(name, 256, 6), a) << name << " ignores its seed";
    }
  }
  EXPECT_EQ(SamplerNames().size(), Samplers().size());
}

TEST(SamplerRegistry, RefusalsSayWhy) {
  auto bad = Sample("jittered", 1000, 1);
  ASSERT_FALSE(bad.ok());
  EXPECT_EQ(bad.status().code(), Status::Code::kInvalidArgument);
  EXPECT_NE(bad.status().message().find("square"), std::string::npos);
  EXPECT_NE(bad.status().message().find("961 or 1024"), std::string::npos);
  for (const char* square_only : {"grid", "uniform-jitter", "jittered"}) {
    EXPECT_FALSE(Sample(square_only, 1000, 1).ok()) << square_only;
    EXPECT_TRUE(Sample(square_only, 1024, 1).ok()) << square_only;
  }
  for (const std::string& name : SamplerNames()) {
    auto zero = Sample(name, 0, 1);
    ASSERT_FALSE(zero.ok()) << name;
    EXPECT_NE(zero.status().message().find(name), std::string::npos) << zero.status().message();
    EXPECT_FALSE(Sample(name, kMaxSamplerPoints + 1, 1).ok()) << name;
  }
  auto unknown = Sample("blue", 64, 1);
  ASSERT_FALSE(unknown.ok());
  EXPECT_NE(unknown.status().message().find("pmj02bn"), std::string::npos);
}

TEST(SamplerRegistry, AnyNIsHonouredByTheGeneralSamplers) {
  for (const std::string& name : SamplerNames()) {
    if (name == "grid" || name == "uniform-jitter" || name == "jittered") continue;
    for (uint32_t n : {1u, 2u, 3u, 97u, 1000u}) {
      EXPECT_EQ(Make(name, n).size(), n) << name;
    }
  }
}

TEST(Stratified, OnePointPerStratum) {
  for (uint32_t m : {1u, 4u, 31u, 32u}) {
    for (const char* name : {"grid", "uniform-jitter", "jittered"}) {
      EXPECT_TRUE(EvenlyStratified(Make(name, m * m), m, m)) << name << " m=" << m;
    }
  }
  // Grid strata centres; uniform jitter shares one offset.
  const PointSet grid = Make("grid", 16);
  EXPECT_EQ(grid[0], (Point2{0.125, 0.125}));
  const PointSet uj = Make("uniform-jitter", 64);
  for (size_t i = 1; i < uj.size(); ++i) {
    EXPECT_NEAR(std::fmod(uj[i].x * 8, 1.0), std::fmod(uj[0].x * 8, 1.0), 1e-9);
  }
}

TEST(Stratified, OnePointPerRowAndColumn) {
  for (uint32_t n : {1u, 16u, 97u, 360u, 1024u, 4096u}) {
    for (const char* name : {"n-rooks", "multi-jittered", "cmj", "rank1-lattice"}) {
      const PointSet p = Make(name, n, 3);
      EXPECT_TRUE(EvenlyStratified(p, n, 1)) << name << " N=" << n;
      EXPECT_TRUE(EvenlyStratified(p, 1, n)) << name << " N=" << n;
    }
    uint32_t m = 0, k = 0;
    MultiJitterShape(n, &m, &k);
    EXPECT_EQ(m * k, n);
    EXPECT_LE(m, k);
    for (const char* name : {"multi-jittered", "cmj"}) {
      EXPECT_TRUE(EvenlyStratified(Make(name, n, 3), m, k)) << name << " N=" << n;
    }
  }
  uint32_t m = 0, k = 0;
  MultiJitterShape(360, &m, &k);
  EXPECT_EQ(m, 18u);
  EXPECT_EQ(k, 20u);
}

TEST(Stratified, CorrelatedMultiJitterSharesOneShuffle) {
  // In CMJ every column uses the same sub-column permutation: the sub-column
  // of cell (i, j) does not depend on i.
  const uint32_t n = 64, m = 8;
  const PointSet p = Make("cmj", n, 9);
  for (uint32_t j = 0; j < m; ++j) {
    const uint32_t first = Bin(p[j * m].x, n) % m;
    for (uint32_t i = 1; i < m; ++i) EXPECT_EQ(Bin(p[j * m + i].x, n) % m, first);
  }
}

TEST(LowDiscrepancy, SobolPrefixesAreNets) {
  const PointSet owen = Make("owen-sobol", 4096, 7), plain = Make("sobol", 4096);
  for (uint32_t size = 1; size <= 4096; size *= 2) {
    EXPECT_TRUE(IsNet(PointSet(owen.begin(), owen.begin() + size)));
    EXPECT_TRUE(IsNet(PointSet(plain.begin(), plain.begin() + size)));
  }
}

TEST(LowDiscrepancy, HammersleyIsANetAtPowersOfTwo) {
  for (uint32_t n : {1u, 2u, 64u, 1024u}) {
    EXPECT_TRUE(IsNet(Make("hammersley", n)));
    EXPECT_TRUE(IsNet(Make("hammersley-scrambled", n, 4)));
  }
}

TEST(LowDiscrepancy, HaltonPrefixesAreStratifiedIn2aBy3b) {
  EXPECT_EQ(RadicalInverse(2, 1), 0.5);
  EXPECT_EQ(RadicalInverse(2, 3), 0.75);
  EXPECT_EQ(RadicalInverse(3, 1), 1.0 / 3.0);
  EXPECT_EQ(RadicalInverse(3, 5), 7.0 / 9.0);
  // The first 2^a 3^b Halton points fill a 2^a x 3^b grid, one per cell;
  // digit permutations keep that.
  for (auto [a, b] : {std::pair{3, 2}, std::pair{5, 1}, std::pair{2, 4}}) {
    const uint32_t cols = 1u << a, rows = static_cast<uint32_t>(std::pow(3, b));
    EXPECT_TRUE(EvenlyStratified(Make("halton", cols * rows), cols, rows));
    EXPECT_TRUE(EvenlyStratified(Make("halton-scrambled", cols * rows, 8), cols, rows));
  }
}

TEST(Rank1, GeneratorsAndMinimumDistance) {
  uint32_t prev = 0;
  EXPECT_TRUE(IsFibonacci(987, &prev));
  EXPECT_EQ(prev, 610u);
  EXPECT_EQ(Rank1Generator(987), 610u);
  EXPECT_FALSE(IsFibonacci(1000, nullptr));
  for (uint32_t n : {89u, 100u, 256u, 1000u}) {
    const uint32_t g = Rank1Generator(n);
    PointSet p = Make("rank1-lattice", n, 2);
    double best = 2.0;
    for (size_t i = 0; i < p.size(); ++i) {
      for (size_t j = i + 1; j < p.size(); ++j) best = std::min(best, TorusDistanceSquared(p[i], p[j]));
    }
    EXPECT_NEAR(std::sqrt(best) * n, Rank1MinDistanceTimesN(n, g), 1e-6) << n;
    // No other generator packs better.
    for (uint32_t h = 1; h < n; ++h) {
      if (std::gcd(h, n) != 1) continue;
      EXPECT_LE(Rank1MinDistanceTimesN(n, h), Rank1MinDistanceTimesN(n, g) + 1e-9) << n << " " << h;
    }
  }
}

double MinTorusDistance(const PointSet& p) {
  double best = 2.0;
  for (size_t i = 0; i < p.size(); ++i) {
    for (size_t j = i + 1; j < p.size(); ++j) best = std::min(best, TorusDistanceSquared(p[i], p[j]));
  }
  return std::sqrt(best);
}

TEST(PoissonDisk, MinimumDistanceHolds) {
  for (uint32_t n : {64u, 1000u, 2048u}) {
    for (uint64_t seed : {1u, 2u}) {
      double r_dart = 0, r_bridson = 0;
      auto dart = PoissonDiskDartThrowing(n, seed, &r_dart);
      auto bridson = PoissonDiskBridson(n, seed, &r_bridson);
      ASSERT_TRUE(dart.ok() && bridson.ok());
      ASSERT_EQ(dart->size(), n);
      ASSERT_EQ(bridson->size(), n);
      const double r_max = HexagonalSpacing(n);
      EXPECT_GE(MinTorusDistance(*dart), r_dart);
      EXPECT_GE(MinTorusDistance(*bridson), r_bridson);
      // Not trivially small: close to what random sequential addition reaches.
      EXPECT_GE(r_dart, 0.65 * r_max) << n;
      EXPECT_GE(r_bridson, 0.65 * r_max) << n;
      // And far above white noise, whose minimum distance is ~1/N.
      EXPECT_GT(MinTorusDistance(*dart), 5.0 / n);
    }
  }
}

}  // namespace
}  // namespace alignset

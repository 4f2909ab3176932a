// The exact variance of a CP-rotated rank-1 lattice, a sum over its dual
// lattice, against the Monte Carlo variance of the same lattice; the dual
// points against a brute-force enumeration; the fast indicator coefficients
// against the general polygon transform.
#include "core/analysis/lattice_variance.h"

#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <utility>

#include "core/analysis/integrands.h"
#include "core/analysis/polygon_fourier.h"
#include "core/analysis/variance.h"
#include "core/optimize/aligned_lattice.h"

namespace alignset {
namespace {

TEST(Rank1DualHalfDisk, MatchesBruteForce) {
  for (auto [n, g] : {std::pair<uint32_t, uint32_t>{64, 23}, {256, 99}, {1000, 377}}) {
    const int r = 90;
    std::set<std::pair<int, int>> expected;
    for (int b = 0; b <= r; ++b) {
      for (int a = -r; a <= r; ++a) {
        if (a * a + b * b > r * r || (b == 0 && a <= 0)) continue;
        if (((a + static_cast<int64_t>(g) * b) % n + n) % n == 0) expected.insert({a, b});
      }
    }
    std::set<std::pair<int, int>> got;
    for (const Frequency& h : Rank1DualHalfDisk(n, g, r)) got.insert({h.a, h.b});
    EXPECT_EQ(got, expected) << "N=" << n << " g=" << g;
    EXPECT_FALSE(expected.empty());
  }
}

TEST(IndicatorSpectrum, MatchesLinearPolygonFourier) {
  const Polygon p = ClipHalfPlane(UnitSquarePolygon(), UnitVector(37.0), 0.9);
  const IndicatorSpectrum fast(p);
  for (auto [a, b] : {std::pair<int, int>{1, 0}, {0, 3}, {-5, 7}, {40, -13}, {300, 227}, {-911, 2}}) {
    const double reference = std::norm(LinearPolygonFourier(p, {}, {double(a), double(b)}));
    EXPECT_NEAR(fast.Energy(a, b), reference, 1e-9 * reference + 1e-18) << a << "," << b;
  }
}

struct Case {
  std::string integrand;
  uint32_t n;
  double theta;  // the lattice's direction
};

class DualAgainstMonteCarlo : public testing::TestWithParam<Case> {};

TEST_P(DualAgainstMonteCarlo, AgreeWithinThreeStandardErrors) {
  const Case& c = GetParam();
  auto f = MakeIntegrand(c.integrand);
  ASSERT_TRUE(f.ok());
  auto choice = ChooseAlignedLatticeGenerator(c.n, {c.theta});
  ASSERT_TRUE(choice.ok()) << choice.status().message();
  const uint32_t g = choice->generator;
  const LatticeVariance exact = Rank1CpVariance(c.n, g, **f, static_cast<int>(16 * c.n));
  const Integrand& fn = **f;
  const VarianceEstimate mc = CranleyPattersonVariance(
      Rank1LatticePoints(c.n, g, 5), [&](const Point2& x) { return fn.Value(x); }, fn.Integral(),
      40000, 11);
  EXPECT_NEAR(exact.extrapolated, mc.variance, 3.0 * mc.std_error)
      << c.integrand << " N=" << c.n << " g=" << g << " head " << exact.head;
  // The extrapolation's correction is a small part of the sum at 16 N.
  EXPECT_LT(exact.extrapolated - exact.head, 0.1 * exact.extrapolated);
}

INSTANTIATE_TEST_SUITE_P(Lattices, DualAgainstMonteCarlo,
                         testing::Values(Case{"step:37:0.1", 256, 37.0},
                                         Case{"step:12:-0.2", 512, 10.0},
                                         Case{"disk", 256, 37.0},
                                         Case{"boundary", 256, 63.0}));

}  // namespace
}  // namespace alignset

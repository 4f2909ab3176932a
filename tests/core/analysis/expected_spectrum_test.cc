// Expected power spectra and their profiles, convergence helpers, and the
// polygon with given edge normals (issue 14).
#include "core/analysis/expected_spectrum.h"

#include <gtest/gtest.h>

#include <cmath>
#include <complex>

#include "core/analysis/convergence.h"
#include "core/analysis/convex_polygon.h"
#include "core/analysis/integrands.h"
#include "core/sampling/samplers.h"
#include "core/spectral/direct_engine.h"
#include "core/spectral/fast_engine.h"
#include "core/util/angles.h"

namespace alignset {
namespace {

double NaivePeriodogram(const PointSet& s, int a, int b) {
  std::complex<double> f = 0.0;
  for (const Point2& p : s) f += std::polar(1.0, -2.0 * kPi * (a * p.x + b * p.y));
  return std::norm(f) / static_cast<double>(s.size());
}

TEST(ExpectedSpectrum, IsTheMeanPeriodogramOfTheSets) {
  const PointSet s1 = *Sample("random", 100, 1);
  const PointSet s2 = *Sample("jittered", 100, 2);
  FastEngine engine(1);
  auto e = ComputeExpectedSpectrum({s1, s2}, 12, engine);
  ASSERT_TRUE(e.ok());
  EXPECT_EQ(e->set_count, 2);
  EXPECT_EQ(e->At(0, 0), 0.0);
  for (int a = -12; a <= 12; a += 5) {
    for (int b = -12; b <= 12; b += 3) {
      if (a == 0 && b == 0) continue;
      const double want = 0.5 * (NaivePeriodogram(s1, a, b) + NaivePeriodogram(s2, a, b));
      EXPECT_NEAR(e->At(a, b), want, 1e-8 * (1.0 + want)) << a << "," << b;
    }
  }
  auto mixed = ComputeExpectedSpectrum({s1, *Sample("random", 64, 1)}, 8, engine);
  EXPECT_EQ(mixed.status().code(), Status::Code::kInvalidArgument);
}

TEST(ExpectedSpectrum, ProfilesAverageTheRightFrequencies) {
  // A synthetic spectrum P(v) = |v|^2 tells which frequencies each profile
  // takes: along 0° exactly (t, 0), so t^2.
  ExpectedSpectrum s;
  s.max_frequency = 20;
  s.power.assign(41 * 41, 0.0);
  for (int a = -20; a <= 20; ++a) {
    for (int b = -20; b <= 20; ++b) s.power[(a + 20) * 41 + (b + 20)] = a * a + b * b;
  }
  const std::vector<double> along0 = DirectionalProfile(s, 0.0);
  for (int t = 1; t <= 20; ++t) EXPECT_DOUBLE_EQ(along0[t], t * t);
  // Along 45° the line passes through (t, t): |v|^2 = 2 t^2 and
  // round(|v.d|) = round(sqrt(2) t).
  const std::vector<double> along45 = DirectionalProfile(s, 45.0);
  EXPECT_DOUBLE_EQ(along45[7], 2.0 * 25.0);  // (5, 5): sqrt(2) 5 = 7.07
  const std::vector<double> radial = RadialProfile(s);
  // Every member of annulus r has (r - 1/2)^2 <= |v|^2 < (r + 1/2)^2.
  for (int r = 1; r <= 20; ++r) {
    EXPECT_GE(radial[r], (r - 0.5) * (r - 0.5)) << r;
    EXPECT_LT(radial[r], (r + 0.5) * (r + 0.5)) << r;
  }
  // Angular: a spectrum that is 1 only within 2° of 30° lights one bin.
  for (int a = -20; a <= 20; ++a) {
    for (int b = -20; b <= 20; ++b) {
      double ang = std::atan2(b, a) * 180.0 / kPi;
      if (ang < 0) ang += 180.0;
      s.power[(a + 20) * 41 + (b + 20)] = std::abs(ang - 30.0) < 2.0 ? 1.0 : 0.0;
    }
  }
  const std::vector<double> angular = AngularProfile(s, 18, 4.0);  // 10° bins
  EXPECT_GT(angular[3], 0.0);                                     // [30°, 40°)
  EXPECT_GT(angular[2], 0.0);                                     // [20°, 30°)
  for (int i : {0, 1, 5, 9, 17}) EXPECT_EQ(angular[i], 0.0) << i;
}

TEST(ExpectedSpectrum, WhiteNoiseIsFlatAtOne) {
  std::vector<PointSet> sets;
  for (uint64_t s = 1; s <= 24; ++s) sets.push_back(*Sample("random", 256, s));
  FastEngine engine(1);
  auto e = ComputeExpectedSpectrum(sets, 24, engine);
  ASSERT_TRUE(e.ok());
  const std::vector<double> radial = RadialProfile(*e);
  for (int r = 4; r <= 24; r += 4) EXPECT_NEAR(radial[r], 1.0, 0.2) << r;
}

TEST(Convergence, RandomSamplingHasVarianceOverNWithAndWithoutShifts) {
  auto f = MakeIntegrand("disk");
  ASSERT_TRUE(f.ok());
  const double var_f = (*f)->SquareIntegral() - (*f)->Integral() * (*f)->Integral();
  std::vector<PointSet> sets;
  for (uint64_t s = 1; s <= 400; ++s) sets.push_back(*Sample("random", 64, s));
  const VarianceEstimate plain = PlainVarianceOverSets(sets, **f);
  EXPECT_NEAR(plain.variance, var_f / 64, 4.0 * plain.std_error);
  EXPECT_LT(plain.std_error, 0.15 * plain.variance);
  std::vector<PointSet> few(sets.begin(), sets.begin() + 8);
  const VarianceEstimate cp = CpVarianceOverSets(few, **f, 256, 5);
  EXPECT_NEAR(cp.variance, var_f / 64, 4.0 * cp.std_error + 0.05 * var_f / 64);
  DirectEngine engine(1);
  const VarianceEstimate exact = ExactCpVarianceOverSets(few, **f, 64, engine);
  EXPECT_NEAR(exact.variance, cp.variance, 4.0 * cp.std_error);
}

TEST(PolygonWithEdgeNormals, HasExactlyTheGivenEdgeDirections) {
  for (int k = 3; k <= 10; ++k) {
    std::vector<double> dirs = {0.0, 90.0};
    for (int i = 0; i < k - 2; ++i) dirs.push_back(11.0 + 170.0 * i / (k - 2) + (i >= 4 ? 3 : 0));
    const Polygon p = PolygonWithEdgeNormals(dirs, 0.7);
    ASSERT_EQ(p.size(), static_cast<size_t>(k)) << k;
    EXPECT_GT(SignedArea(p), 0.03) << k;
    for (size_t i = 0; i < p.size(); ++i) {
      const Vec2 a = p[i], b = p[(i + 1) % p.size()];
      EXPECT_GE(std::min(a.x, a.y), 0.15 - 1e-12);
      EXPECT_LE(std::max(a.x, a.y), 0.85 + 1e-12);
      // The edge's normal is one of the directions, modulo 180°.
      double normal = std::atan2(a.x - b.x, b.y - a.y) * 180.0 / kPi;
      normal = ReduceDirection(normal);
      double best = 180.0;
      for (double d : dirs) {
        const double gap = std::fabs(ReduceDirection(d) - normal);
        best = std::min(best, std::min(gap, 180.0 - gap));
      }
      EXPECT_LT(best, 1e-9) << "k=" << k << " edge " << i << " normal " << normal;
    }
  }
  EXPECT_TRUE(PolygonWithEdgeNormals({0, 90, 90}, 0.7).empty());
  EXPECT_TRUE(PolygonWithEdgeNormals({0, 90}, 0.7).empty());
}

}  // namespace
}  // namespace alignset

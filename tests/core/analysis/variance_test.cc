#include "core/analysis/variance.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/util/hash.h"
#include "core/analysis/step_integrand.h"

namespace alignset {
namespace {

TEST(StepIntegrand, ExactIntegralsOfKnownCuts) {
  EXPECT_NEAR(StepIntegrand(0).Integral(), 0.5, 1e-15);
  EXPECT_NEAR(StepIntegrand(45).Integral(), 0.5, 1e-15);
  EXPECT_NEAR(StepIntegrand(0, 0.25).Integral(), 0.25, 1e-15);
  EXPECT_NEAR(StepIntegrand(180, 0.25).Integral(), 0.25, 1e-15);
  // Normal 45°, through (0.75, 0.75): the corner triangle with legs 0.5.
  EXPECT_NEAR(StepIntegrand(45, 0.25 * std::sqrt(2.0)).Integral(), 0.125, 1e-12);
}

TEST(StepIntegrand, IntegralAgreesWithAFineGrid) {
  for (double deg : {10.0, 77.0, 133.0, 260.0}) {
    const StepIntegrand f(deg, 0.1);
    const int m = 1000;
    double sum = 0;
    for (int i = 0; i < m; ++i)
      for (int j = 0; j < m; ++j) sum += f({(i + 0.5) / m, (j + 0.5) / m});
    EXPECT_NEAR(sum / (m * m), f.Integral(), 2e-3) << deg;
  }
}

TEST(Variance, RandomPointsGiveVarianceOfFOverN) {
  // For i.i.d. uniform points, Var = Var(f) / N = p(1-p) / N.
  const StepIntegrand f(30, 0.1);
  const double p = f.Integral();
  Pcg32 rng(5);
  const int n = 64;
  PointSet pts(n);
  // Average over independent random sets: the CP variance of one random set
  // is itself random around p(1-p)/N.
  double mean = 0;
  const int sets = 64;
  for (int s = 0; s < sets; ++s) {
    for (auto& q : pts) q = {rng.NextDouble(), rng.NextDouble()};
    mean += CranleyPattersonVariance(pts, f, p, 1024, s).variance / sets;
  }
  EXPECT_NEAR(mean / (p * (1 - p) / n), 1.0, 0.08);
}

TEST(Variance, GridOnAnAxisEdgeIsExact) {
  // A 16 x 16 regular grid and a vertical edge at x = 15/32: the region
  // x >= 15/32 is 8.5 columns wide, so a shifted grid puts 8 or 9 of its 16
  // columns inside, each with probability 1/2. The error is +-1/32 and the
  // CP variance exactly 1/1024.
  PointSet grid;
  for (int i = 0; i < 16; ++i)
    for (int j = 0; j < 16; ++j) grid.push_back({(i + 0.5) / 16, (j + 0.5) / 16});
  const StepIntegrand f(0, -1.0 / 32);
  EXPECT_DOUBLE_EQ(f.Integral(), 17.0 / 32);
  const VarianceEstimate v = CranleyPattersonVariance(grid, f, f.Integral(), 4096, 1);
  EXPECT_NEAR(v.variance, 1.0 / 1024, 1e-12);
}

TEST(Variance, LogLogSlopeRecoversAPowerLaw) {
  const std::vector<double> n = {256, 1024, 4096};
  std::vector<double> v;
  for (double x : n) v.push_back(3.0 * std::pow(x, -1.75));
  EXPECT_NEAR(LogLogSlope(n, v), -1.75, 1e-12);
}

}  // namespace
}  // namespace alignset

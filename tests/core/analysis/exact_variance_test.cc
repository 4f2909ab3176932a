// Supplement Eq. 18 (exact CP variance from the periodogram and the
// integrand's Fourier coefficients) against the Monte Carlo CP variance of the
// same set: they must agree within 3 standard errors of the Monte Carlo
// figure (plus the documented truncation estimate's own slack).
#include "core/analysis/exact_variance.h"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "core/analysis/integrands.h"
#include "core/analysis/variance.h"
#include "core/sampling/samplers.h"
#include "core/spectral/direct_engine.h"

namespace alignset {
namespace {

struct Pair {
  std::string integrand;
  std::string sampler;
  uint32_t n;
};

class ExactAgainstMonteCarlo : public testing::TestWithParam<Pair> {};

TEST_P(ExactAgainstMonteCarlo, AgreeWithinThreeStandardErrors) {
  const Pair& p = GetParam();
  auto f = MakeIntegrand(p.integrand);
  ASSERT_TRUE(f.ok());
  auto points = Sample(p.sampler, p.n, 3);
  ASSERT_TRUE(points.ok()) << points.status().message();
  DirectEngine engine(2);
  const DiskSpectrum spectrum = ComputeDiskSpectrum(*points, 384, engine);
  const ExactVariance exact = ExactCpVariance(spectrum, **f);
  const Integrand& g = **f;
  const VarianceEstimate mc = CranleyPattersonVariance(
      *points, [&](const Point2& x) { return g.Value(x); }, g.Integral(), 40000, 17);
  // The truncated tail is estimated as tail_energy / N; allow it to be off by
  // half of itself on top of the Monte Carlo error.
  const double allowed = 3.0 * mc.std_error + 0.5 * exact.tail_estimate;
  EXPECT_NEAR(exact.variance, mc.variance, allowed)
      << p.integrand << " x " << p.sampler << ": exact " << exact.variance << " (head "
      << exact.head << ", tail " << exact.tail_estimate << "), Monte Carlo " << mc.variance
      << " +- " << mc.std_error;
  // The check has teeth: the tail is a small part and the figures are not
  // trivially equal to zero.
  EXPECT_LT(exact.tail_estimate, 0.1 * exact.variance);
  EXPECT_GT(exact.head, 0.0);
}

INSTANTIATE_TEST_SUITE_P(
    IntegrandsAndSamplers, ExactAgainstMonteCarlo,
    testing::Values(Pair{"gaussian", "owen-sobol", 256}, Pair{"product", "random", 256},
                    Pair{"product", "owen-sobol", 256}, Pair{"smoothstep:30", "jittered", 256},
                    Pair{"disk", "owen-sobol", 256}, Pair{"triangle", "random", 256},
                    Pair{"step:30", "pmj02bn", 256}, Pair{"boundary", "random", 256}),
    [](const testing::TestParamInfo<Pair>& info) {
      std::string s = info.param.integrand + "_" + info.param.sampler;
      for (char& c : s) {
        if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
      }
      return s;
    });

TEST(ExactVariance, WhiteNoiseAveragesToVarianceOverN) {
  // E over random sets of P_S(v) is 1, so the mean exact variance over
  // random sets is Var(f) / N.
  auto f = MakeIntegrand("disk");
  ASSERT_TRUE(f.ok());
  DirectEngine engine(2);
  const uint32_t n = 128;
  double mean = 0;
  const int sets = 40;
  for (int s = 0; s < sets; ++s) {
    auto pts = Sample("random", n, 100 + s);
    ASSERT_TRUE(pts.ok());
    mean += ExactCpVariance(ComputeDiskSpectrum(*pts, 128, engine), **f).variance / sets;
  }
  const double var_f = (*f)->SquareIntegral() - (*f)->Integral() * (*f)->Integral();
  EXPECT_NEAR(mean, var_f / n, 0.15 * var_f / n);
}

}  // namespace
}  // namespace alignset

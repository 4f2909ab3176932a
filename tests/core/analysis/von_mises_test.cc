#include "core/analysis/von_mises.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "core/util/angles.h"

namespace alignset {
namespace {

TEST(Bessel, MatchesTheStandardLibraryWhereItIsFinite) {
  for (double k : {1e-8, 1e-3, 0.1, 0.5, 1.0, 3.0, 10.0, 29.999, 30.0, 30.001, 45.0, 100.0, 300.0,
                   700.0}) {
    const double i0 = std::cyl_bessel_i(0.0, k), i1 = std::cyl_bessel_i(1.0, k);
    EXPECT_NEAR(BesselRatio(k), i1 / i0, 1e-14 * (i1 / i0)) << k;
    EXPECT_NEAR(LogBesselI0(k), std::log(i0), 1e-13 * std::max(1.0, std::log(i0))) << k;
  }
  EXPECT_EQ(BesselRatio(0.0), 0.0);
  EXPECT_EQ(LogBesselI0(0.0), 0.0);
}

TEST(Bessel, StableForLargeKappa) {
  // Past ~700 I0 overflows a double; the ratio and log I0 stay finite and
  // follow A = 1 - 1/(2k) - 1/(8k^2) - ..., log I0 = k - log(2 pi k)/2 + 1/(8k) + ...
  double prev = BesselRatio(700.0);
  for (double k : {1e3, 1e4, 1e6, 1e9, 1e12}) {
    const double a = BesselRatio(k);
    ASSERT_TRUE(std::isfinite(a)) << k;
    EXPECT_LT(a, 1.0);
    EXPECT_GE(a, prev);
    EXPECT_NEAR(1.0 - a, 1.0 / (2 * k) + 1.0 / (8 * k * k), 1e-3 / (k * k) + 1e-16) << k;
    EXPECT_NEAR(LogBesselI0(k), k - 0.5 * std::log(2 * kPi * k) + 1.0 / (8 * k), 1e-9 * k) << k;
    prev = a;
  }
  // Continuous where the method switches.
  EXPECT_NEAR(BesselRatio(kBesselSwitch * (1 - 1e-12)), BesselRatio(kBesselSwitch), 1e-13);
}

// log p of a mixture of two von Mises lobes plus a floor, on n bins.
std::vector<double> MixtureLogP(int n, double mu1, double k1, double w1, double mu2, double k2) {
  std::vector<double> lp(n);
  for (int i = 0; i < n; ++i) {
    const double x = (i + 0.5) * 2 * kPi / n;
    const double p = w1 * std::exp(k1 * (std::cos(x - mu1) - 1)) +
                     (1 - w1) * std::exp(k2 * (std::cos(x - mu2) - 1)) + 1e-3;
    lp[i] = std::log(p);
  }
  return lp;
}

TEST(ReverseKl, GradientMatchesFiniteDifferences) {
  const auto lp = MixtureLogP(2048, 1.1, 40.0, 0.7, 4.0, 10.0);
  for (double lambda : {0.0, 1e-3}) {
    for (auto [mu, k] : {std::pair{1.0, 0.5}, {1.3, 5.0}, {0.7, 40.0}, {1.15, 400.0}, {3.5, 12.0}}) {
      double gm = 0, gk = 0;
      ReverseKlGradient(lp, mu, k, lambda, &gm, &gk);
      const double hm = 1e-6, hk = 1e-6 * k;
      const double fm = (ReverseKl(lp, mu + hm, k, lambda) - ReverseKl(lp, mu - hm, k, lambda)) / (2 * hm);
      const double fk = (ReverseKl(lp, mu, k + hk, lambda) - ReverseKl(lp, mu, k - hk, lambda)) / (2 * hk);
      EXPECT_NEAR(gm, fm, 1e-6 * std::max(1.0, std::fabs(fm))) << mu << " " << k;
      EXPECT_NEAR(gk, fk, 1e-6 * std::max(1e-3, std::fabs(fk))) << mu << " " << k;
    }
  }
}

TEST(ReverseKl, IsZeroAtTheTargetItself) {
  // p = q(mu, kappa) exactly: KL(q || p) = 0 and the gradient vanishes.
  const int n = 2048;
  std::vector<double> lp(n);
  const double mu = 2.0, k = 25.0;
  for (int i = 0; i < n; ++i) {
    const double x = (i + 0.5) * 2 * kPi / n;
    lp[i] = k * std::cos(x - mu) - std::log(2 * kPi) - LogBesselI0(k);
  }
  EXPECT_NEAR(ReverseKl(lp, mu, k, 0.0), 0.0, 1e-12);
  double gm = 1, gk = 1;
  ReverseKlGradient(lp, mu, k, 0.0, &gm, &gk);
  EXPECT_NEAR(gm, 0.0, 1e-10);
  EXPECT_NEAR(gk, 0.0, 1e-10);
}

TEST(FitVonMises, RecoversAVonMisesTarget) {
  const int n = 2048;
  std::vector<double> lp(n);
  const double mu = 5.9, k = 60.0;  // near 2pi: the fit wraps
  for (int i = 0; i < n; ++i) {
    const double x = (i + 0.5) * 2 * kPi / n;
    lp[i] = k * std::cos(x - mu) - std::log(2 * kPi) - LogBesselI0(k);
  }
  VonMisesFitOptions o;
  o.lambda = 0.0;
  const VonMisesFit fit = FitVonMises(lp, 5.7, 10.0, o);
  EXPECT_NEAR(fit.mu, mu, 1e-5);
  EXPECT_NEAR(fit.kappa, k, 1e-3 * k);
  EXPECT_NEAR(fit.objective, 0.0, 1e-9);
  // lambda kappa^2 shrinks kappa, never moves mu.
  o.lambda = 1e-3;
  const VonMisesFit shrunk = FitVonMises(lp, 5.7, 10.0, o);
  EXPECT_LT(shrunk.kappa, 0.95 * k);
  EXPECT_NEAR(shrunk.mu, mu, 1e-5);
}

TEST(FitVonMises, IsModeSeekingOnTwoLobes) {
  // Reverse KL locks onto the stronger lobe instead of averaging the two
  // (a forward fit would sit between them with a small kappa).
  const auto lp = MixtureLogP(2048, 1.0, 60.0, 0.6, 2.2, 60.0);
  VonMisesFitOptions o;
  const VonMisesFit fit = FitVonMises(lp, 1.2, 5.0, o);
  EXPECT_NEAR(fit.mu, 1.0, 0.01);
  EXPECT_GT(fit.kappa, 30.0);
}

TEST(FitVonMises, NeverRaisesTheObjective) {
  const auto lp = MixtureLogP(1024, 0.3, 20.0, 0.5, 3.0, 20.0);
  VonMisesFitOptions o;
  for (int iters : {0, 1, 2, 5, 20, 200}) {
    o.max_iterations = iters;
    const VonMisesFit fit = FitVonMises(lp, 1.5, 2.0, o);
    EXPECT_LE(fit.objective, ReverseKl(lp, 1.5, 2.0, o.lambda) + 1e-15) << iters;
    EXPECT_LE(fit.kappa, MaxResolvedKappa(1024));
  }
}

}  // namespace
}  // namespace alignset

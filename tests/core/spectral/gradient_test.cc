// Analytic gradients against central finite differences (with one Richardson
// step, so the truncation error is O(h^4) and the comparison can be tight).
#include <gtest/gtest.h>

#include <cmath>
#include <functional>

#include "core/spectral/direct_engine.h"
#include "core/spectral/frequency_set.h"
#include "core/sampling/owen_sobol.h"
#include "core/optimize/sliced_wasserstein.h"

namespace alignset {
namespace {

double Richardson(const std::function<double(double)>& f, double x, double h) {
  auto central = [&](double step) { return (f(x + step) - f(x - step)) / (2 * step); };
  return (4 * central(h / 2) - central(h)) / 3;
}

struct Case {
  uint32_t n;
  std::vector<double> dirs;
};

// Relative error of every checked component against the RMS of the analytic
// gradient (single components can be near zero).
void ExpectGradientMatches(const PointSet& base, const std::vector<Point2>& grad,
                           const std::function<double(const PointSet&)>& loss, double h,
                           double tolerance) {
  double rms = 0;
  for (const Point2& g : grad) rms += g.x * g.x + g.y * g.y;
  rms = std::sqrt(rms / (2 * grad.size()));
  ASSERT_GT(rms, 0);
  for (size_t j = 0; j < base.size(); j += std::max<size_t>(1, base.size() / 12)) {
    for (int axis = 0; axis < 2; ++axis) {
      auto f = [&](double t) {
        PointSet p = base;
        (axis == 0 ? p[j].x : p[j].y) = t;
        return loss(p);
      };
      const double x0 = axis == 0 ? base[j].x : base[j].y;
      const double fd = Richardson(f, x0, h);
      const double an = axis == 0 ? grad[j].x : grad[j].y;
      EXPECT_LT(std::abs(fd - an) / rms, tolerance)
          << "point " << j << " axis " << axis << " fd " << fd << " analytic " << an;
    }
  }
}

TEST(Gradient, SpectrumLossMatchesFiniteDifferences) {
  const Case cases[] = {{64, {30}}, {128, {10, 70}}, {256, {120}}, {300, {45}}};
  for (const Case& c : cases) {
    SCOPED_TRACE("N=" + std::to_string(c.n));
    DirectEngine engine(2);
    engine.SetFrequencies(BuildFrequencySet(DefaultFrequencyParams(c.n), AnisotropyDirections(c.dirs)));
    const PointSet pts = OwenScrambledSobol(c.n, 5);
    SpectrumEvaluation e;
    engine.Evaluate(pts, true, &e);
    auto loss = [&](const PointSet& p) {
      SpectrumEvaluation x;
      engine.Evaluate(p, false, &x);
      return x.loss;
    };
    ExpectGradientMatches(pts, e.gradient, loss, 1e-5, 1e-5);
  }
}

// Loss weights w_v (decaying like |v|^-3, as the optimizer's low-frequency
// weighting does) change the loss and its gradient consistently.
TEST(Gradient, WeightedSpectrumLossMatchesFiniteDifferences) {
  const Case cases[] = {{64, {30}}, {200, {10, 70}}};
  for (const Case& c : cases) {
    SCOPED_TRACE("N=" + std::to_string(c.n));
    DirectEngine engine(2);
    const auto k = BuildFrequencySet(DefaultFrequencyParams(c.n), AnisotropyDirections(c.dirs));
    engine.SetFrequencies(k);
    std::vector<double> w;
    for (const Frequency& v : k) w.push_back(std::pow(std::hypot(v.a, v.b), -3.0));
    engine.SetLossWeights(w);
    const PointSet pts = OwenScrambledSobol(c.n, 5);
    SpectrumEvaluation e;
    engine.Evaluate(pts, true, &e);
    double expected = 0;
    for (size_t q = 0; q < k.size(); ++q) expected += w[q] * std::norm(e.spectrum[q]);
    EXPECT_NEAR(e.loss, expected / (c.n * static_cast<double>(k.size())), 1e-12 * expected);
    auto loss = [&](const PointSet& p) {
      SpectrumEvaluation x;
      engine.Evaluate(p, false, &x);
      return x.loss;
    };
    ExpectGradientMatches(pts, e.gradient, loss, 1e-5, 1e-5);
  }
}

TEST(DirectEngine, WeightedSpectrumMatchesNaiveSums) {
  const PointSet pts = OwenScrambledSobol(70, 3);
  const auto k = BuildFrequencySet({12, 3, 5}, AnisotropyDirections({21}));
  std::vector<double> f;
  for (size_t j = 0; j < pts.size(); ++j) f.push_back(std::sin(0.37 * j) + 0.25);
  DirectEngine engine(2);
  engine.SetFrequencies(k);
  std::vector<std::complex<double>> got;
  engine.EvaluateWeighted(pts, f, &got);
  ASSERT_EQ(got.size(), k.size());
  for (size_t q = 0; q < k.size(); ++q) {
    std::complex<double> want = 0;
    for (size_t j = 0; j < pts.size(); ++j) {
      want += f[j] * std::polar(1.0, -2 * M_PI * (k[q].a * pts[j].x + k[q].b * pts[j].y));
    }
    EXPECT_LT(std::abs(want - got[q]), 1e-11) << k[q].a << "," << k[q].b;
  }
  // Unit strengths give Evaluate's spectrum.
  SpectrumEvaluation plain;
  engine.Evaluate(pts, false, &plain);
  engine.EvaluateWeighted(pts, std::vector<double>(pts.size(), 1.0), &got);
  for (size_t q = 0; q < k.size(); ++q) EXPECT_LT(std::abs(got[q] - plain.spectrum[q]), 1e-12);
}

TEST(Gradient, SlicedWassersteinMatchesFiniteDifferences) {
  const Case cases[] = {{64, {30}}, {200, {10, 70}}, {256, {135}}};
  for (const Case& c : cases) {
    SCOPED_TRACE("N=" + std::to_string(c.n));
    const SlicedWasserstein sw(c.n, AnisotropyDirections(c.dirs));
    const PointSet pts = OwenScrambledSobol(c.n, 9);
    std::vector<Point2> grad;
    sw.Evaluate(pts, &grad);
    // Small enough that no projection changes rank within +-h.
    ExpectGradientMatches(pts, grad, [&](const PointSet& p) { return sw.Evaluate(p, nullptr); },
                          1e-9, 1e-5);
  }
}

TEST(DirectEngine, MatchesNaiveSumsAndLoss) {
  const PointSet pts = OwenScrambledSobol(50, 2);
  const auto k = BuildFrequencySet({20, 3, 4}, AnisotropyDirections({33}));
  DirectEngine engine(3);
  engine.SetFrequencies(k);
  SpectrumEvaluation e;
  engine.Evaluate(pts, false, &e);
  ASSERT_EQ(e.spectrum.size(), k.size());
  double power = 0;
  for (size_t q = 0; q < k.size(); ++q) {
    std::complex<double> f = 0;
    for (const Point2& p : pts) {
      f += std::polar(1.0, -2 * M_PI * (k[q].a * p.x + k[q].b * p.y));
    }
    EXPECT_LT(std::abs(f - e.spectrum[q]), 1e-11) << k[q].a << "," << k[q].b;
    power += std::norm(f);
  }
  EXPECT_NEAR(e.loss, power / (pts.size() * k.size()), 1e-12);
}

TEST(DirectEngine, ResultIsIndependentOfTheThreadCount) {
  const PointSet pts = OwenScrambledSobol(1000, 4);
  const auto k = BuildFrequencySet(DefaultFrequencyParams(1000), AnisotropyDirections({17}));
  SpectrumEvaluation one, three;
  DirectEngine e1(1), e3(3);
  e1.SetFrequencies(k);
  e3.SetFrequencies(k);
  e1.Evaluate(pts, true, &one);
  e3.Evaluate(pts, true, &three);
  EXPECT_EQ(one.spectrum, three.spectrum);
  EXPECT_EQ(one.loss, three.loss);
  EXPECT_EQ(one.gradient, three.gradient);
}

}  // namespace
}  // namespace alignset

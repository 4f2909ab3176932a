// The folded (cosine) spectrum of a step edge against the general polygon
// transform at half-integer frequencies, and the variance of a lattice
// shifted before the tent fold, a sum of it over the dual points, against
// the Monte Carlo variance of the same lattice.
#include "core/analysis/folded_indicator_spectrum.h"

#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <utility>

#include "core/analysis/lattice_variance.h"
#include "core/analysis/polygon_fourier.h"
#include "core/analysis/variance.h"
#include "core/optimize/aligned_lattice.h"
#include "core/util/angles.h"

namespace alignset {
namespace {

double Tent(double u) { return 1.0 - std::abs(2.0 * u - 1.0); }

// c(h) = int_P cos(pi h_x x) cos(pi h_y y) = 1/4 sum over the four sign
// pairs of P^(+-h_x / 2, +-h_y / 2), from the general transform.
double CosineCoefficient(const Polygon& p, int hx, int hy) {
  std::complex<double> sum = 0.0;
  for (int sx : {-1, 1}) {
    for (int sy : {-1, 1}) sum += LinearPolygonFourier(p, {}, {0.5 * sx * hx, 0.5 * sy * hy});
  }
  return 0.25 * sum.real();
}

TEST(FoldedIndicatorSpectrum, IsTheSquaredCosineCoefficient) {
  for (auto [theta, offset] : {std::pair<double, double>{37.0, 0.1}, {10.0, -0.2}, {82.0, 0.0}, {135.0, 0.3}}) {
    const Vec2 n = UnitVector(theta);
    const Polygon p = ClipHalfPlane(UnitSquarePolygon(), n, 0.5 * (n.x + n.y) + offset);
    const FoldedIndicatorSpectrum folded(p, 64);
    for (auto [a, b] : {std::pair<int, int>{1, 0}, {0, 1}, {2, 0}, {3, 5}, {-4, 7}, {17, 30}, {-63, 2}, {120, 77}}) {
      const double c = CosineCoefficient(p, a, b);
      EXPECT_NEAR(folded.Energy(a, b), c * c, 1e-9 * c * c + 1e-20)
          << "theta " << theta << " h=(" << a << "," << b << ")";
    }
  }
}

struct FoldCase {
  uint32_t n;
  double theta;   // the lattice's direction
  double edge;    // the edge's normal
  double offset;  // along the normal, from the centre
};

class FoldedDualAgainstMonteCarlo : public testing::TestWithParam<FoldCase> {};

TEST_P(FoldedDualAgainstMonteCarlo, AgreeWithinThreeStandardErrors) {
  const FoldCase& c = GetParam();
  AlignedLatticeOptions folded;
  folded.folded = true;
  auto choice = ChooseAlignedLatticeGenerator(c.n, {c.theta}, folded);
  ASSERT_TRUE(choice.ok()) << choice.status().message();
  const uint32_t g = choice->generator;
  const Vec2 nv = UnitVector(c.edge);
  const double threshold = 0.5 * (nv.x + nv.y) + c.offset;
  const Polygon p = ClipHalfPlane(UnitSquarePolygon(), nv, threshold);
  const int radius = static_cast<int>(16 * c.n);
  const FoldedIndicatorSpectrum spectrum(p, radius);
  double head = 0.0, half = 0.0;
  for (const Frequency& h : Rank1DualHalfDisk(c.n, g, radius)) {
    const double e = 2.0 * spectrum.Energy(h.a, h.b);  // +-h
    head += e;
    if (h.a * h.a + h.b * h.b <= radius * radius / 4) half += e;
  }
  const double exact = std::max(head, 2.0 * head - half);
  // The unshifted lattice, shifted by the CP rotation and then folded: the
  // tent-folded lattice's randomization.
  PointSet lattice(c.n);
  for (uint32_t i = 0; i < c.n; ++i) {
    lattice[i] = {static_cast<double>(i) / c.n, static_cast<double>((uint64_t{i} * g) % c.n) / c.n};
  }
  const VarianceEstimate mc = CranleyPattersonVariance(
      lattice,
      [&](const Point2& x) { return Tent(x.x) * nv.x + Tent(x.y) * nv.y >= threshold ? 1.0 : 0.0; },
      SignedArea(p), 40000, 17);
  EXPECT_NEAR(exact, mc.variance, 3.0 * mc.std_error) << "N=" << c.n << " g=" << g << " head " << head;
  EXPECT_LT(exact - head, 0.1 * exact);
}

INSTANTIATE_TEST_SUITE_P(Lattices, FoldedDualAgainstMonteCarlo,
                         testing::Values(FoldCase{256, 37.0, 37.0, 0.1}, FoldCase{1024, 30.0, 30.0, 0.15},
                                         FoldCase{1024, 30.0, 30.5, -0.2}, FoldCase{512, 10.0, 12.0, 0.2}));

}  // namespace
}  // namespace alignset

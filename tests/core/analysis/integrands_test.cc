// The integrand family's closed forms against independent quadrature.
#include "core/analysis/integrands.h"

#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <functional>

#include "core/analysis/convex_polygon.h"
#include "core/analysis/polygon_fourier.h"
#include "core/util/gauss_legendre.h"

namespace alignset {
namespace {

using Complex = std::complex<double>;

// Product Gauss-Legendre over a triangle in collapsed coordinates
// x = p0 + s (p1 - p0) + s t (p2 - p1), Jacobian 2 A s: exact to rounding for
// the entire integrands below at moderate frequencies.
Complex TriangleQuadrature(const Vec2& p0, const Vec2& p1, const Vec2& p2,
                           const std::function<Complex(Vec2)>& g) {
  std::vector<double> t, w;
  GaussLegendre(100, &t, &w);
  const double area2 = (p1.x - p0.x) * (p2.y - p0.y) - (p2.x - p0.x) * (p1.y - p0.y);
  Complex sum = 0.0;
  for (size_t i = 0; i < t.size(); ++i) {
    const double s = 0.5 * (t[i] + 1.0);
    for (size_t j = 0; j < t.size(); ++j) {
      const double u = 0.5 * (t[j] + 1.0);
      const Vec2 x = {p0.x + s * (p1.x - p0.x) + s * u * (p2.x - p1.x),
                      p0.y + s * (p1.y - p0.y) + s * u * (p2.y - p1.y)};
      sum += 0.25 * w[i] * w[j] * area2 * s * g(x);
    }
  }
  return sum;
}

Complex PolygonQuadrature(const Polygon& p, const std::function<Complex(Vec2)>& g) {
  Complex sum = 0.0;
  for (size_t i = 1; i + 1 < p.size(); ++i) sum += TriangleQuadrature(p[0], p[i], p[i + 1], g);
  return sum;
}

TEST(ConvexPolygon, ClipAreaAndIntegrals) {
  const Polygon square = UnitSquarePolygon();
  EXPECT_DOUBLE_EQ(SignedArea(square), 1.0);
  // x + y >= 1: the upper-right triangle.
  const Polygon half = ClipHalfPlane(square, {1, 1}, 1.0);
  EXPECT_NEAR(SignedArea(half), 0.5, 1e-15);
  EXPECT_TRUE(ClipHalfPlane(square, {1, 0}, 2.0).empty());
  const LinearFunction h{0.3, {1.5, -0.7}};
  const Complex want = PolygonQuadrature(half, [&](Vec2 x) { return Complex(h(x)); });
  EXPECT_NEAR(IntegrateLinear(half, h), want.real(), 1e-13);
  const Complex want2 = PolygonQuadrature(half, [&](Vec2 x) { return Complex(h(x) * h(x)); });
  EXPECT_NEAR(IntegrateLinearSquared(half, h), want2.real(), 1e-13);
  EXPECT_TRUE(ContainsPoint(half, {0.9, 0.9}));
  EXPECT_FALSE(ContainsPoint(half, {0.2, 0.3}));
}

TEST(PolygonFourier, MatchesQuadratureForLinearFunctions) {
  const std::vector<Polygon> polygons = {
      {{0.1, 0.2}, {0.9, 0.35}, {0.4, 0.8}},
      RegularPolygon({0.5, 0.5}, 0.3, 7, 11.0),
      ClipHalfPlane(UnitSquarePolygon(), {std::cos(0.6), std::sin(0.6)}, 0.7)};
  const std::vector<LinearFunction> functions = {{1.0, {0, 0}}, {0.2, {0.8, -1.3}}};
  const std::vector<Vec2> frequencies = {{0, 0},  {1, 0},    {0, -3},     {5, 2},   {-7, 11},
                                         {1e-9, 0}, {0.3, 1e-7}, {12.5, -4.25}, {20, 20}};
  for (const Polygon& p : polygons) {
    for (const LinearFunction& h : functions) {
      for (const Vec2& v : frequencies) {
        const Complex want = PolygonQuadrature(p, [&](Vec2 x) {
          return h(x) * std::polar(1.0, -2.0 * kPi * (v.x * x.x + v.y * x.y));
        });
        const Complex got = LinearPolygonFourier(p, h, v);
        EXPECT_LT(std::abs(got - want), 1e-12)
            << "v=(" << v.x << "," << v.y << ") got " << got << " want " << want;
      }
    }
  }
}

TEST(Integrands, SmoothedStepIsContinuousAndItsIntegralsAreExact) {
  const auto f = SmoothedStep(35.0, 0.2, 0.05);
  // On the edge line the ramp is 1/2; at +-width/2 it meets 0 and 1.
  const Vec2 n = {std::cos(DegToRad(35.0)), std::sin(DegToRad(35.0))};
  const Vec2 c = {0.5 + 0.05 * n.x, 0.5 + 0.05 * n.y};
  EXPECT_NEAR(f->Value({c.x, c.y}), 0.5, 1e-12);
  EXPECT_NEAR(f->Value({c.x + 0.0999 * n.x, c.y + 0.0999 * n.y}), 0.9995, 1e-9);
  EXPECT_NEAR(f->Value({c.x + 0.1001 * n.x, c.y + 0.1001 * n.y}), 1.0, 1e-12);
  EXPECT_EQ(f->Value({c.x - 0.11 * n.x, c.y - 0.11 * n.y}), 0.0);
  // Integrals against a fine midpoint grid.
  const int m = 1200;
  double sum = 0, sum2 = 0;
  for (int i = 0; i < m; ++i) {
    for (int j = 0; j < m; ++j) {
      const double v = f->Value({(i + 0.5) / m, (j + 0.5) / m});
      sum += v;
      sum2 += v * v;
    }
  }
  EXPECT_NEAR(sum / (m * m), f->Integral(), 2e-5);
  EXPECT_NEAR(sum2 / (m * m), f->SquareIntegral(), 2e-5);
}

TEST(Integrands, DiskFourierMatchesPolarQuadrature) {
  const DiskIntegrand disk({0.45, 0.55}, 0.3);
  std::vector<double> t, w;
  GaussLegendre(64, &t, &w);
  for (auto [a, b] : std::vector<std::pair<int, int>>{{0, 0}, {1, 0}, {2, -3}, {7, 4}}) {
    Complex want = 0.0;
    for (size_t i = 0; i < t.size(); ++i) {
      const double r = 0.15 * (t[i] + 1.0);
      for (int k = 0; k < 256; ++k) {  // trapezoid in angle: exact for trig polynomials
        const double phi = 2.0 * kPi * k / 256;
        const double x = 0.45 + r * std::cos(phi), y = 0.55 + r * std::sin(phi);
        want += 0.15 * w[i] * r * (2.0 * kPi / 256) * std::polar(1.0, -2.0 * kPi * (a * x + b * y));
      }
    }
    EXPECT_LT(std::abs(disk.Fourier(a, b) - want), 1e-12) << a << "," << b;
  }
  EXPECT_EQ(disk.Value({0.45, 0.55}), 1.0);
  EXPECT_EQ(disk.Value({0.45, 0.86}), 0.0);
}

TEST(Integrands, GaussianCoefficientsAndIntegralsMatchQuadrature) {
  const auto g = SeparableIntegrand::ClippedGaussian(0.5, 0.15);
  std::vector<double> t, w;
  GaussLegendre(200, &t, &w);
  auto profile = [](double x) { return std::exp(-(x - 0.5) * (x - 0.5) / (2 * 0.15 * 0.15)); };
  double i1 = 0, i2 = 0;
  for (size_t i = 0; i < t.size(); ++i) {
    const double x = 0.5 * (t[i] + 1.0);
    i1 += 0.5 * w[i] * profile(x);
    i2 += 0.5 * w[i] * profile(x) * profile(x);
  }
  EXPECT_NEAR(g->Integral(), i1 * i1, 1e-14);
  EXPECT_NEAR(g->SquareIntegral(), i2 * i2, 1e-14);
  for (auto [a, b] : std::vector<std::pair<int, int>>{{1, 0}, {3, -2}, {-5, 9}, {40, 1}}) {
    Complex ca = 0, cb = 0;
    for (size_t i = 0; i < t.size(); ++i) {
      const double x = 0.5 * (t[i] + 1.0);
      ca += 0.5 * w[i] * profile(x) * std::polar(1.0, -2.0 * kPi * a * x);
      cb += 0.5 * w[i] * profile(x) * std::polar(1.0, -2.0 * kPi * b * x);
    }
    EXPECT_LT(std::abs(g->Fourier(a, b) - ca * cb), 1e-14) << a << "," << b;
  }
  // Parseval on the 1-D profile: sum_a |g^(a)|^2 = integral g^2 (the tail
  // beyond kMaxFrequency falls like 1/a^2 from the clipped ends: negligible).
  // Fourier(a, 0) = g^(a) g^(0), Integral = g^(0)^2, SquareIntegral = (int g^2)^2.
  double energy = 0;
  for (int a = -SeparableIntegrand::kMaxFrequency; a <= SeparableIntegrand::kMaxFrequency; ++a) {
    energy += std::norm(g->Fourier(a, 0));
  }
  EXPECT_NEAR(energy, std::sqrt(g->SquareIntegral()) * g->Integral(), 1e-8 * energy);
}

TEST(Integrands, CosineProductHasOnlyTheLowestFrequencies) {
  const auto f = SeparableIntegrand::CosineProduct();
  EXPECT_DOUBLE_EQ(f->Integral(), 0.25);
  EXPECT_NEAR(std::abs(f->Fourier(1, -1)), 1.0 / 16, 1e-15);
  EXPECT_EQ(std::abs(f->Fourier(2, 0)), 0.0);
  double energy = 0;
  for (int a = -2; a <= 2; ++a)
    for (int b = -2; b <= 2; ++b) energy += std::norm(f->Fourier(a, b));
  EXPECT_NEAR(energy, f->SquareIntegral(), 1e-15);
  EXPECT_NEAR(f->Value({0.5, 0.0}), 0.0, 1e-15);
}

TEST(Integrands, SpecsParseAndBadSpecsAreRefused) {
  for (const std::string& spec : IntegrandFamilySpecs(30.0)) {
    auto f = MakeIntegrand(spec);
    ASSERT_TRUE(f.ok()) << spec << ": " << f.status().message();
    EXPECT_GT((*f)->Integral(), 0.0) << spec;
  }
  for (const std::string& spec : {"step:30:0.1", "smoothstep:10:0.05:0.1", "disk:0.2:0.3:0.4",
                                  "polygon:7:15", "gaussian:0.2", "boundary"}) {
    EXPECT_TRUE(MakeIntegrand(spec).ok()) << spec;
  }
  for (const std::string& spec : {"", "step", "step:nan", "step:1:2:3", "disk:0.7", "polygon:2",
                                  "polygon:3.5", "blob", "gaussian:-1", "smoothstep:30:0"}) {
    auto f = MakeIntegrand(spec);
    EXPECT_FALSE(f.ok()) << spec;
    if (!f.ok()) EXPECT_FALSE(f.status().message().empty());
  }
  // step:210 is the complement of step:30.
  auto a = MakeIntegrand("step:30"), b = MakeIntegrand("step:210");
  EXPECT_NEAR((*a)->Integral() + (*b)->Integral(), 1.0, 1e-14);
}

}  // namespace
}  // namespace alignset

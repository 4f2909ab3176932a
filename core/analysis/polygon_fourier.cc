#include "core/analysis/polygon_fourier.h"

#include <cmath>
#include <utility>
#include <vector>

#include "core/util/gauss_legendre.h"

namespace alignset {
namespace {

using Complex = std::complex<double>;

// E0(z) = integral_0^1 exp(z t) dt and E1(z) = integral_0^1 t exp(z t) dt for
// z = -2 pi i u. The closed forms (e^z - 1)/z and (e^z (z - 1) + 1)/z^2 lose
// digits as z -> 0; below |z| = 1 the Taylor series converge fast (terms fall
// like 1/k!) and are used instead.
void EdgeMoments(double u, Complex* e0, Complex* e1) {
  const Complex z(0.0, -2.0 * kPi * u);
  if (std::abs(z) < 1.0) {
    Complex s0 = 0.0, s1 = 0.0, zk = 1.0;
    double factorial = 1.0;  // k!
    for (int k = 0; k < 24; ++k) {
      if (k > 0) factorial *= k;
      s0 += zk / (factorial * (k + 1));
      s1 += zk / (factorial * (k + 2));
      zk *= z;
    }
    *e0 = s0;
    *e1 = s1;
    return;
  }
  const Complex ez = std::exp(z);
  *e0 = (ez - 1.0) / z;
  *e1 = (ez * (z - 1.0) + 1.0) / (z * z);
}

// Below |v| = kSmallFrequency the edge sum cancels like 1/|v|^2; there the
// integrand is so smooth that a collapsed 16 x 16 Gauss-Legendre rule per
// triangle of a fan is exact to rounding, so it is used instead.
constexpr double kSmallFrequency = 0.5;

Complex SmallFrequencyFourier(const Polygon& polygon, const LinearFunction& h, Vec2 v) {
  static const auto rule = [] {
    std::pair<std::vector<double>, std::vector<double>> r;
    GaussLegendre(16, &r.first, &r.second);
    return r;
  }();
  const std::vector<double>& t = rule.first;
  const std::vector<double>& w = rule.second;
  Complex sum = 0.0;
  for (size_t i = 1; i + 1 < polygon.size(); ++i) {
    const Vec2& p0 = polygon[0];
    const Vec2& p1 = polygon[i];
    const Vec2& p2 = polygon[i + 1];
    const double area2 = (p1.x - p0.x) * (p2.y - p0.y) - (p2.x - p0.x) * (p1.y - p0.y);
    for (size_t a = 0; a < t.size(); ++a) {
      const double s = 0.5 * (t[a] + 1.0);
      for (size_t b = 0; b < t.size(); ++b) {
        const double u = 0.5 * (t[b] + 1.0);
        // x = p0 + s (p1 - p0) + s u (p2 - p1), Jacobian area2 * s.
        const Vec2 x = {p0.x + s * (p1.x - p0.x) + s * u * (p2.x - p1.x),
                        p0.y + s * (p1.y - p0.y) + s * u * (p2.y - p1.y)};
        sum += 0.25 * w[a] * w[b] * area2 * s * h(x) *
               std::polar(1.0, -2.0 * kPi * (v.x * x.x + v.y * x.y));
      }
    }
  }
  return sum;
}

}  // namespace

std::complex<double> LinearPolygonFourier(const Polygon& polygon, const LinearFunction& h,
                                          Vec2 v) {
  const double v2 = v.x * v.x + v.y * v.y;
  if (v2 == 0.0) return IntegrateLinear(polygon, h);
  if (v2 < kSmallFrequency * kSmallFrequency) return SmallFrequencyFourier(polygon, h, v);
  const Complex alpha(0.0, 1.0 / (2.0 * kPi * v2));
  const double beta = (h.g.x * v.x + h.g.y * v.y) / (4.0 * kPi * kPi * v2 * v2);
  Complex sum = 0.0;
  const size_t k = polygon.size();
  for (size_t i = 0; i < k; ++i) {
    const Vec2& p0 = polygon[i];
    const Vec2& p1 = polygon[(i + 1) % k];
    const Vec2 d = {p1.x - p0.x, p1.y - p0.y};
    // (v . outward normal) ds for a counter-clockwise edge, ds = |d| dt.
    const double flux = v.x * d.y - v.y * d.x;
    if (flux == 0.0) continue;
    const double u = v.x * d.x + v.y * d.y;
    Complex e0, e1;
    EdgeMoments(u, &e0, &e1);
    const double h0 = h(p0), h1 = h(p1);
    const Complex phase = std::polar(1.0, -2.0 * kPi * (v.x * p0.x + v.y * p0.y));
    sum += flux * phase * ((alpha * h0 + beta) * e0 + alpha * (h1 - h0) * e1);
  }
  return sum;
}

}  // namespace alignset

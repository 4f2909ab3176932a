#include "core/analysis/lattice_variance.h"

#include <algorithm>
#include <cmath>

namespace alignset {

std::vector<Frequency> Rank1DualHalfDisk(uint32_t n, uint32_t g, int radius) {
  std::vector<Frequency> out;
  if (radius <= 0 || n == 0) return out;
  const int64_t nn = n, r = radius, r2 = r * r;
  // Row h_y = k holds h_x = -g k (mod N) + j N; the half disk is h_y > 0, or
  // h_y = 0 and h_x > 0.
  for (int64_t k = 0; k <= r; ++k) {
    const int64_t base = ((-static_cast<int64_t>(g) * k) % nn + nn) % nn;  // in [0, N)
    // The smallest h_x = base + j N with h_x >= -r.
    int64_t hx = base - ((base + r) / nn) * nn;
    for (; hx <= r; hx += nn) {
      if (k == 0 && hx <= 0) continue;
      if (hx * hx + k * k > r2) continue;
      out.push_back({static_cast<int32_t>(hx), static_cast<int32_t>(k)});
    }
  }
  return out;
}

LatticeVariance Rank1CpVariance(uint32_t n, uint32_t g, const Integrand& f, int radius) {
  LatticeVariance v;
  v.radius = radius;
  const double half = 0.5 * radius;
  for (const Frequency& h : Rank1DualHalfDisk(n, g, radius)) {
    // Both h and -h: |f^(-h)| = |f^(h)| for real f.
    const double e = 2.0 * std::norm(f.Fourier(h.a, h.b));
    v.head += e;
    if (std::hypot(static_cast<double>(h.a), static_cast<double>(h.b)) <= half) v.half_radius += e;
  }
  v.extrapolated = std::max(v.head, 2.0 * v.head - v.half_radius);
  return v;
}

namespace {
double Sinc(double x) {  // sin(pi x) / (pi x)
  if (std::abs(x) < 1e-8) return 1.0;
  return std::sin(kPi * x) / (kPi * x);
}
}  // namespace

IndicatorSpectrum::IndicatorSpectrum(const Polygon& p) {
  for (size_t i = 0; i < p.size(); ++i) {
    const Vec2 a = p[i], b = p[(i + 1) % p.size()];
    const double ex = b.x - a.x, ey = b.y - a.y;
    if (std::hypot(ex, ey) < 1e-14) continue;
    edges_.push_back({ex, ey, 0.5 * (a.x + b.x), 0.5 * (a.y + b.y)});
  }
}

double IndicatorSpectrum::Energy(double hx, double hy) const {
  double re = 0.0, im = 0.0;
  for (const Edge& e : edges_) {
    const double w = (hx * e.ey - hy * e.ex) * Sinc(hx * e.ex + hy * e.ey);
    // The phase reduced mod 1 first: h . m reaches N / 2 at large radii.
    double t = hx * e.mx + hy * e.my;
    t -= std::floor(t);
    re += w * std::cos(2.0 * kPi * t);
    im -= w * std::sin(2.0 * kPi * t);
  }
  const double h2 = hx * hx + hy * hy;
  return (re * re + im * im) / (4.0 * kPi * kPi * h2 * h2);
}

}  // namespace alignset

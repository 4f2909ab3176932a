#include "core/analysis/integer_indicator_spectrum.h"

#include <cmath>
#include <cstdlib>

#include "core/util/angles.h"

namespace alignset {
namespace {

// A coordinate this close to 0 or 1 is on the square's side: its factor is
// 1 for every integer frequency (clipping leaves such vertices within a few
// ulps of the side).
constexpr double kOnSide = 1e-13;
// Below this |h . e| the difference E(a) - E(b) is replaced by the series:
// the difference divides the factors' rounding (about |h| 1e-16, from
// reducing h . p mod 1) by 2 pi |h . e|; at 1e-4 that cost 1e-9 of an
// energy at |h| = 300, at 0.05 it is 1e-12 at |h| = 2048.
constexpr double kSmallArgument = 0.05;
// 1 / (k + 1)!, k = 0 ... 12.
constexpr int kSeriesTerms = 13;
constexpr double kSeries[kSeriesTerms] = {
    1.0,          1.0 / 2,       1.0 / 6,        1.0 / 24,        1.0 / 120,
    1.0 / 720,    1.0 / 5040,    1.0 / 40320,    1.0 / 362880,    1.0 / 3628800,
    1.0 / 39916800, 1.0 / 479001600, 1.0 / 6227020800.0};

bool OnSide(double t) { return std::abs(t) <= kOnSide || std::abs(t - 1.0) <= kOnSide; }

std::complex<double> Phase(double t) {
  // exp(-2 pi i t), t reduced mod 1 first: h . p reaches N / 2.
  t -= std::floor(t);
  return {std::cos(2.0 * kPi * t), -std::sin(2.0 * kPi * t)};
}

}  // namespace

IntegerIndicatorSpectrum::IntegerIndicatorSpectrum(const Polygon& p, int radius, bool tabulate)
    : radius_(radius) {
  if (p.size() > kMaxVertices) return;  // refused: Valid() says so
  for (size_t i = 0; i < p.size(); ++i) {
    Vertex v;
    v.x = p[i].x, v.y = p[i].y;
    v.x_trivial = OnSide(v.x), v.y_trivial = OnSide(v.y);
    if (tabulate && radius > 0) {
      if (!v.x_trivial) {
        v.xs.resize(2 * static_cast<size_t>(radius) + 1);
        for (int h = -radius; h <= radius; ++h) v.xs[static_cast<size_t>(h + radius)] = Phase(h * v.x);
      }
      if (!v.y_trivial) {
        v.ys.resize(static_cast<size_t>(radius) + 1);
        for (int h = 0; h <= radius; ++h) v.ys[static_cast<size_t>(h)] = Phase(h * v.y);
      }
    }
    vertices_.push_back(std::move(v));
  }
  // IndicatorSpectrum's edges: counter-clockwise, the degenerate ones left
  // out.
  for (size_t i = 0; i < p.size(); ++i) {
    const size_t j = (i + 1) % p.size();
    const double ex = p[j].x - p[i].x, ey = p[j].y - p[i].y;
    if (std::hypot(ex, ey) < 1e-14) continue;
    edges_.push_back({i, j, ex, ey});
  }
}

size_t IntegerIndicatorSpectrum::TableBytes() const {
  size_t bytes = 0;
  for (const Vertex& v : vertices_) bytes += (v.xs.size() + v.ys.size()) * sizeof(Complex);
  return bytes;
}

IntegerIndicatorSpectrum::Complex IntegerIndicatorSpectrum::Exponential(const Vertex& v, int hx,
                                                                        int hy) const {
  double re = 1.0, im = 0.0;
  if (!v.x_trivial) {
    const Complex x = !v.xs.empty() && std::abs(hx) <= radius_ ? v.xs[static_cast<size_t>(hx + radius_)]
                                                               : Phase(hx * v.x);
    re = x.real(), im = x.imag();
  }
  if (!v.y_trivial) {
    const Complex y = !v.ys.empty() && hy >= 0 && hy <= radius_ ? v.ys[static_cast<size_t>(hy)]
                                                                : Phase(hy * v.y);
    // By hand: std::complex's product checks for infinities on every call.
    const double r = re * y.real() - im * y.imag();
    im = re * y.imag() + im * y.real();
    re = r;
  }
  return {re, im};
}

std::complex<double> IntegerIndicatorSpectrum::Sum(int hx, int hy) const {
  // Every vertex's factor once: a polygon has a handful (the constructor
  // keeps at most kMaxVertices).
  double fr[kMaxVertices], fi[kMaxVertices];
  for (size_t i = 0; i < vertices_.size(); ++i) {
    const Complex e = Exponential(vertices_[i], hx, hy);
    fr[i] = e.real(), fi[i] = e.imag();
  }
  const double fx = hx, fy = hy;
  double sr = 0.0, si = 0.0;
  for (const Edge& edge : edges_) {
    const double u = fx * edge.ex + fy * edge.ey;
    const double cross = fx * edge.ey - fy * edge.ex;
    const double ar = fr[edge.a], ai = fi[edge.a];
    double tr, ti;
    if (std::abs(u) >= kSmallArgument) {
      // (E(a) - E(b)) / (2 pi i u) = -i (E(a) - E(b)) / (2 pi u).
      const double scale = cross / (2.0 * kPi * u);
      tr = (ai - fi[edge.b]) * scale;
      ti = -(ar - fr[edge.b]) * scale;
    } else {
      // E(a) (1 - exp(-z)) / z with z = 2 pi i u, by its series
      // sum_k (-z)^k / (k + 1)! (Horner; at |z| <= 2 pi kSmallArgument the
      // terms left out are below 1e-17).
      const double w = 2.0 * kPi * u;
      double cr = kSeries[kSeriesTerms - 1], ci = 0.0;
      for (int k = kSeriesTerms - 2; k >= 0; --k) {
        // (cr + i ci) (-i w) + 1 / (k + 1)!
        const double r = ci * w + kSeries[k];
        ci = -cr * w;
        cr = r;
      }
      tr = cross * (ar * cr - ai * ci);
      ti = cross * (ar * ci + ai * cr);
    }
    sr += tr, si += ti;
  }
  return {sr, si};
}

double IntegerIndicatorSpectrum::Energy(int hx, int hy) const {
  const Complex s = Sum(hx, hy);
  const double h2 = static_cast<double>(hx) * hx + static_cast<double>(hy) * hy;
  return (s.real() * s.real() + s.imag() * s.imag()) / (4.0 * kPi * kPi * h2 * h2);
}

double SymmetricUnionEnergy(const IntegerIndicatorSpectrum* half, size_t count, int hx, int hy) {
  double si = 0.0;
  for (size_t i = 0; i < count; ++i) si += half[i].Sum(hx, hy).imag();
  const double h2 = static_cast<double>(hx) * hx + static_cast<double>(hy) * hy;
  return (si * si) / (kPi * kPi * h2 * h2);
}

}  // namespace alignset

#include "core/optimize/low_frequency_projection.h"

#include <algorithm>
#include <cmath>
#include <complex>

#include "core/util/angles.h"

namespace alignset {
namespace {

// Solves the symmetric positive (semi)definite system A x = b in place by
// Cholesky with a tiny diagonal floor (A = J J^T is singular only when two
// constraints coincide, which distinct frequencies never do on a set of
// more than a handful of points).
void SolveSpd(std::vector<double> a, size_t m, std::vector<double>* b) {
  double diag_max = 0.0;
  for (size_t i = 0; i < m; ++i) diag_max = std::max(diag_max, a[i * m + i]);
  const double floor = 1e-14 * std::max(diag_max, 1e-300);
  for (size_t j = 0; j < m; ++j) {
    double d = a[j * m + j];
    for (size_t k = 0; k < j; ++k) d -= a[j * m + k] * a[j * m + k];
    d = std::sqrt(std::max(d, floor));
    a[j * m + j] = d;
    for (size_t i = j + 1; i < m; ++i) {
      double s = a[i * m + j];
      for (size_t k = 0; k < j; ++k) s -= a[i * m + k] * a[j * m + k];
      a[i * m + j] = s / d;
    }
  }
  std::vector<double>& x = *b;
  for (size_t i = 0; i < m; ++i) {
    double s = x[i];
    for (size_t k = 0; k < i; ++k) s -= a[i * m + k] * x[k];
    x[i] = s / a[i * m + i];
  }
  for (size_t i = m; i-- > 0;) {
    double s = x[i];
    for (size_t k = i + 1; k < m; ++k) s -= a[k * m + i] * x[k];
    x[i] = s / a[i * m + i];
  }
}

}  // namespace

std::vector<Frequency> LowFrequencies(double radius) {
  return BuildFrequencySet({1.0, 1.0, radius}, {});
}

double ProjectLowFrequencies(PointSet* points, const std::vector<Frequency>& frequencies,
                             int iterations) {
  const size_t n = points->size();
  const size_t nv = frequencies.size();
  if (n == 0 || nv == 0) return 0.0;
  const size_t m = 2 * nv;
  // Per point and constraint: the gradient of Re F(v) and Im F(v) is
  // -2 pi (sin, cos)(2 pi v.s_j) times v, so each constraint row is a
  // scalar per point times v; only the scalars are stored.
  std::vector<double> g(m * n);
  std::vector<double> r(m), a(m * m);
  double worst = 0.0;
  for (int step = 0; step <= iterations; ++step) {
    std::fill(r.begin(), r.end(), 0.0);
    for (size_t q = 0; q < nv; ++q) {
      const Frequency& v = frequencies[q];
      double* gre = &g[(2 * q) * n];
      double* gim = &g[(2 * q + 1) * n];
      for (size_t j = 0; j < n; ++j) {
        const double ph = v.a * (*points)[j].x + v.b * (*points)[j].y;
        const double frac = ph - std::floor(ph);
        const double c = std::cos(2.0 * kPi * frac), s = std::sin(2.0 * kPi * frac);
        r[2 * q] += c;
        r[2 * q + 1] -= s;
        gre[j] = -2.0 * kPi * s;
        gim[j] = -2.0 * kPi * c;
      }
    }
    worst = 0.0;
    for (size_t q = 0; q < nv; ++q) {
      worst = std::max(worst, (r[2 * q] * r[2 * q] + r[2 * q + 1] * r[2 * q + 1]) / n);
    }
    if (step == iterations) break;
    // A = J J^T with J's row p at point j equal to g_p(j) v_p.
    for (size_t p = 0; p < m; ++p) {
      const Frequency& vp = frequencies[p / 2];
      for (size_t q = 0; q <= p; ++q) {
        const Frequency& vq = frequencies[q / 2];
        const double dot = static_cast<double>(vp.a) * vq.a + static_cast<double>(vp.b) * vq.b;
        double s = 0.0;
        const double* gp = &g[p * n];
        const double* gq = &g[q * n];
        for (size_t j = 0; j < n; ++j) s += gp[j] * gq[j];
        a[p * m + q] = a[q * m + p] = s * dot;
      }
    }
    std::vector<double> lambda = r;
    SolveSpd(a, m, &lambda);
    // delta_j = -sum_p lambda_p g_p(j) v_p.
    for (size_t j = 0; j < n; ++j) {
      double dx = 0.0, dy = 0.0;
      for (size_t p = 0; p < m; ++p) {
        const double w = lambda[p] * g[p * n + j];
        dx += w * frequencies[p / 2].a;
        dy += w * frequencies[p / 2].b;
      }
      Point2& s = (*points)[j];
      s.x = Wrap01(s.x - dx);
      s.y = Wrap01(s.y - dy);
    }
  }
  return worst;
}

}  // namespace alignset

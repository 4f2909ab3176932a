#include "core/optimize/low_frequency_projection.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdlib>
#include <vector>

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
  // e^{2 pi i v.s_j} = (e^{2 pi i x_j})^a (e^{2 pi i y_j})^b: two sines and
  // cosines per point and step, and products, instead of one per point and
  // frequency (the projection runs four times at the end of every
  // optimization, and the sines were most of its cost).
  int amax = 0, bmax = 0;
  for (const Frequency& v : frequencies) {
    amax = std::max(amax, std::abs(v.a));
    bmax = std::max(bmax, std::abs(v.b));
  }
  std::vector<std::complex<double>> xpow((static_cast<size_t>(amax) + 1) * n);
  std::vector<std::complex<double>> ypow((static_cast<size_t>(bmax) + 1) * n);
  auto powers = [n](double coordinate, size_t j, int top, std::complex<double>* out) {
    const double t = 2.0 * kPi * (coordinate - std::floor(coordinate));
    const std::complex<double> e(std::cos(t), std::sin(t));
    out[j] = 1.0;
    for (size_t k = 1; k <= static_cast<size_t>(top); ++k) out[k * n + j] = out[(k - 1) * n + j] * e;
  };
  double worst = 0.0;
  for (int step = 0; step <= iterations; ++step) {
    for (size_t j = 0; j < n; ++j) {
      powers((*points)[j].x, j, amax, xpow.data());
      powers((*points)[j].y, j, bmax, ypow.data());
    }
    std::fill(r.begin(), r.end(), 0.0);
    for (size_t q = 0; q < nv; ++q) {
      const Frequency& v = frequencies[q];
      const std::complex<double>* ex = &xpow[static_cast<size_t>(std::abs(v.a)) * n];
      const std::complex<double>* ey = &ypow[static_cast<size_t>(std::abs(v.b)) * n];
      double* gre = &g[(2 * q) * n];
      double* gim = &g[(2 * q + 1) * n];
      for (size_t j = 0; j < n; ++j) {
        const std::complex<double> e = (v.a < 0 ? std::conj(ex[j]) : ex[j]) *
                                       (v.b < 0 ? std::conj(ey[j]) : ey[j]);
        const double c = e.real(), s = e.imag();
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
    // A = J J^T with J's row p at point j equal to g_p(j) v_p. The sums
    // over points run in blocks that stay in the first-level cache for all
    // m (m + 1) / 2 pairs, with four running sums each so that they
    // vectorize.
    constexpr size_t kBlock = 128;
    std::vector<double> sums(m * m * 4, 0.0);
    for (size_t begin = 0; begin < n; begin += kBlock) {
      const size_t end = std::min(n, begin + kBlock);
      for (size_t p = 0; p < m; ++p) {
        const double* gp = &g[p * n];
        for (size_t q = 0; q <= p; ++q) {
          const double* gq = &g[q * n];
          double* s4 = &sums[(p * m + q) * 4];
          size_t j = begin;
          for (; j + 4 <= end; j += 4) {
            for (size_t l = 0; l < 4; ++l) s4[l] += gp[j + l] * gq[j + l];
          }
          for (; j < end; ++j) s4[0] += gp[j] * gq[j];
        }
      }
    }
    for (size_t p = 0; p < m; ++p) {
      const Frequency& vp = frequencies[p / 2];
      for (size_t q = 0; q <= p; ++q) {
        const Frequency& vq = frequencies[q / 2];
        const double dot = static_cast<double>(vp.a) * vq.a + static_cast<double>(vp.b) * vq.b;
        const double* s4 = &sums[(p * m + q) * 4];
        a[p * m + q] = a[q * m + p] = ((s4[0] + s4[1]) + (s4[2] + s4[3])) * dot;
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

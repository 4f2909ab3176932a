#include "core/spectral/nufft_kernel.h"

#include <algorithm>
#include <cmath>

#include "core/util/angles.h"
#include "core/util/gauss_legendre.h"

namespace alignset {

void EsKernel::BuildPolynomials() {
  // Tap t at offset y in [-1, 1] sits at z = (y + width - 1) / 2 - t.
  degree_ = std::min(TapPolynomialDegree(width_), kMaxDegree);
  const int nodes = degree_ + 1;
  coefficients_.assign(static_cast<size_t>(degree_ + 1) * width_, 0.0);
  // Monomial coefficients of the Chebyshev polynomials T_0 .. T_degree.
  std::vector<std::vector<long double>> cheb(nodes, std::vector<long double>(nodes, 0.0L));
  cheb[0][0] = 1.0L;
  if (nodes > 1) cheb[1][1] = 1.0L;
  for (int k = 2; k < nodes; ++k) {
    for (int d = 0; d < nodes; ++d) {
      cheb[k][d] = (d > 0 ? 2.0L * cheb[k - 1][d - 1] : 0.0L) - cheb[k - 2][d];
    }
  }
  for (int t = 0; t < width_; ++t) {
    // Chebyshev interpolant through the Chebyshev points of the first kind.
    std::vector<long double> f(nodes), a(nodes, 0.0L);
    for (int i = 0; i < nodes; ++i) {
      const long double y = std::cos(static_cast<long double>(kPi) * (i + 0.5L) / nodes);
      f[i] = Value(static_cast<double>((y + width_ - 1) / 2.0L - t));
    }
    for (int k = 0; k < nodes; ++k) {
      long double s = 0.0L;
      for (int i = 0; i < nodes; ++i) {
        s += f[i] * std::cos(static_cast<long double>(kPi) * k * (i + 0.5L) / nodes);
      }
      a[k] = (k == 0 ? 1.0L : 2.0L) * s / nodes;
    }
    for (int d = 0; d < nodes; ++d) {
      long double c = 0.0L;
      for (int k = 0; k < nodes; ++k) c += a[k] * cheb[k][d];
      coefficients_[static_cast<size_t>(d) * width_ + t] = static_cast<double>(c);
    }
  }
}

EsKernel::EsKernel(double tolerance) {
  tolerance = std::clamp(tolerance, 1e-14, 1e-2);
  // Width and shape as recommended for oversampling 2: about one digit per
  // grid point of support, beta = 2.30 * width.
  width_ = std::clamp(static_cast<int>(std::ceil(-std::log10(tolerance / 10.0))), 2, kMaxWidth);
  beta_ = 2.30 * width_;
  half_width_ = 0.5 * width_;
  inv_half_width_ = 1.0 / half_width_;
  // phi is analytic inside the support but its derivatives blow up at the
  // ends (damped by exp(-beta)); generous node counts make the quadrature
  // error far below the truncation error of the kernel itself.
  BuildPolynomials();
  std::vector<double> x, w;
  GaussLegendre(4 * width_ + 24, &x, &w);
  for (size_t i = 0; i < x.size(); ++i) {
    if (x[i] <= 0.0) continue;  // phi is even: integrate over [0, w/2], double
    nodes_.push_back(half_width_ * x[i]);
    quad_weights_.push_back(half_width_ * w[i]);
  }
}

double EsKernel::Value(double z) const {
  const double t = z * inv_half_width_;
  const double s = 1.0 - t * t;
  if (s < 0.0) return 0.0;
  return std::exp(beta_ * (std::sqrt(s) - 1.0));
}

int EsKernel::Weights(double x, double* values) const {
  const int first = static_cast<int>(std::ceil(x - half_width_));
  const double y = 2.0 * (x - first) - width_ + 1.0;
  const double* c = &coefficients_[static_cast<size_t>(degree_) * width_];
  for (int t = 0; t < width_; ++t) values[t] = c[t];
  for (int d = degree_ - 1; d >= 0; --d) {
    c -= width_;
    for (int t = 0; t < width_; ++t) values[t] = values[t] * y + c[t];
  }
  return first;
}

int EsKernel::ExactWeights(double x, double* values) const {
  const int first = static_cast<int>(std::ceil(x - half_width_));
  const double z0 = x - first;
  for (int t = 0; t < width_; ++t) {
    const double u = (z0 - t) * inv_half_width_;
    const double s = std::max(1.0 - u * u, 0.0);
    values[t] = beta_ * (std::sqrt(s) - 1.0);
  }
  for (int t = 0; t < width_; ++t) values[t] = std::exp(values[t]);
  return first;
}

std::vector<double> EsKernel::FourierTransform(int n, int max_mode) const {
  std::vector<double> phi(nodes_.size());
  for (size_t i = 0; i < nodes_.size(); ++i) phi[i] = quad_weights_[i] * Value(nodes_[i]);
  std::vector<double> out(static_cast<size_t>(max_mode) + 1);
  for (int k = 0; k <= max_mode; ++k) {
    double s = 0.0;
    const double f = 2.0 * kPi * k / n;
    for (size_t i = 0; i < nodes_.size(); ++i) s += phi[i] * std::cos(f * nodes_[i]);
    out[k] = 2.0 * s;
  }
  return out;
}

}  // namespace alignset

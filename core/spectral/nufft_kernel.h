#pragma once

#include <cmath>
#include <vector>

namespace alignset {

// The "exponential of semicircle" spreading kernel of the NUFFT (Barnett,
// Magland, af Klinteberg 2019), in grid units:
//   phi(z) = exp(beta (sqrt(1 - (2 z / width)^2) - 1))   for |z| <= width / 2,
// used on grids oversampled by kOversampling. Its width follows the requested
// relative tolerance: each extra grid point of support buys about one decimal
// digit.
// Degree of the polynomial that stands for each kernel tap (see
// EsKernel::Weights): one more than the width already reaches the error of
// the kernel's own truncation at the support ends (~tolerance / 20).
constexpr int TapPolynomialDegree(int width) { return width + 1; }

class EsKernel {
 public:
  static constexpr int kOversampling = 2;
  static constexpr int kMaxWidth = 16;

  // tolerance is clamped to [1e-14, 1e-2].
  explicit EsKernel(double tolerance);

  int width() const { return width_; }
  double beta() const { return beta_; }

  // phi(z); zero outside the support.
  double Value(double z) const;

  // The width kernel values phi(x - (first + t)), t in [0, width), at the
  // grid points nearest to a coordinate x (in grid units), where
  // first = ceil(x - width / 2). Returns first.
  //
  // Each tap is a smooth function of the fractional offset, tabulated as a
  // polynomial (Chebyshev interpolant, evaluated by Horner's rule): a few
  // vectorizable multiply-adds instead of an exp and a sqrt per tap,
  // accurate to about tolerance / 20 of phi's maximum.
  int Weights(double x, double* values) const;
  // The same for a width known at compile time (W == width()), which lets
  // the compiler unroll and vectorize the taps.
  template <int W>
  int Weights(double x, double* values) const;

  // The tap polynomials: coefficients()[d * width + t] multiplies y^d for
  // tap t, d = 0 .. degree(), y = 2 (x - first) - width + 1 in [-1, 1].
  int degree() const { return degree_; }
  const double* coefficients() const { return coefficients_.data(); }

  // The same by direct evaluation of phi (reference for the polynomial).
  int ExactWeights(double x, double* values) const;

  // The continuous Fourier transform phi_hat(k) = integral of
  // phi(z) exp(2 pi i k z / n) dz for k = 0 .. max_mode on a grid of n
  // points (real and even since phi is), by Gauss-Legendre quadrature.
  std::vector<double> FourierTransform(int n, int max_mode) const;

 private:
  void BuildPolynomials();

  int width_;
  double beta_;
  double half_width_;
  double inv_half_width_;
  static constexpr int kMaxDegree = kMaxWidth + 8;
  int degree_;
  // coefficients_[d * width + t]: coefficient of y^d for tap t, with
  // y = 2 (x - first) - width + 1 in [-1, 1].
  std::vector<double> coefficients_;
  // Gauss-Legendre nodes and weights on [0, width / 2].
  std::vector<double> nodes_;
  std::vector<double> quad_weights_;
};

template <int W>
int EsKernel::Weights(double x, double* values) const {
  const int first = static_cast<int>(std::ceil(x - 0.5 * W));
  const double y = 2.0 * (x - first) - (W - 1);
  const double* c = &coefficients_[static_cast<size_t>(degree_) * W];
  double v[W];
  for (int t = 0; t < W; ++t) v[t] = c[t];
  for (int d = degree_ - 1; d >= 0; --d) {
    c -= W;
    for (int t = 0; t < W; ++t) v[t] = v[t] * y + c[t];
  }
  for (int t = 0; t < W; ++t) values[t] = v[t];
  return first;
}

}  // namespace alignset

#pragma once

#include <complex>
#include <string>

#include "core/util/point_set.h"

namespace alignset {

// A test integrand on the unit square, with what the exact variance of a
// Cranley-Patterson-rotated estimator needs (method.md section 4):
//   Var = sum over v != 0 of P_S(v) |f^(v)|^2 / N,
// where f^(v) = integral over [0,1)^2 of f(x) exp(-2 pi i v.x) dx are the
// Fourier-series coefficients of f periodized on the torus (so the square's
// own edges are discontinuities of it, unless f matches across them).
class Integrand {
 public:
  virtual ~Integrand() = default;

  // A short name that says what it is, e.g. "step 30deg".
  virtual std::string name() const = 0;
  // f at a point of [0,1)^2.
  virtual double Value(const Point2& p) const = 0;
  // The exact integral of f and of f^2 over [0,1)^2. The second gives the
  // total spectral energy (Parseval), hence the exact energy beyond any
  // truncation of the Fourier sum.
  virtual double Integral() const = 0;
  virtual double SquareIntegral() const = 0;
  // f^(v) at the integer frequency v = (a, b).
  virtual std::complex<double> Fourier(int a, int b) const = 0;
};

}  // namespace alignset

#pragma once

#include <memory>
#include <string>
#include <vector>

#include "core/analysis/convex_polygon.h"
#include "core/analysis/integrand.h"
#include "core/util/status.h"

namespace alignset {

// Non-overlapping convex pieces, each with its own linear function, and 0
// elsewhere: steps, ramps (smoothed steps), polygons, flat and linearly
// shaded regions. Everything is exact: values, integrals, Fourier
// coefficients (polygon_fourier.h).
class PiecewiseLinearIntegrand final : public Integrand {
 public:
  struct Piece {
    Polygon polygon;  // counter-clockwise, inside the unit square
    LinearFunction h;
  };
  PiecewiseLinearIntegrand(std::string name, std::vector<Piece> pieces);

  std::string name() const override { return name_; }
  double Value(const Point2& p) const override;
  double Integral() const override { return integral_; }
  double SquareIntegral() const override { return square_integral_; }
  std::complex<double> Fourier(int a, int b) const override;
  const std::vector<Piece>& pieces() const { return pieces_; }

 private:
  std::string name_;
  std::vector<Piece> pieces_;
  double integral_ = 0.0;
  double square_integral_ = 0.0;
};

// The indicator of a disk (periodized: it may cross the square's edges).
// f^(v) = r J1(2 pi r |v|) / |v| exp(-2 pi i v.c).
class DiskIntegrand final : public Integrand {
 public:
  DiskIntegrand(Vec2 centre, double radius);
  std::string name() const override;
  double Value(const Point2& p) const override;
  double Integral() const override;
  double SquareIntegral() const override { return Integral(); }
  std::complex<double> Fourier(int a, int b) const override;

 private:
  Vec2 centre_;
  double radius_;
};

// f(x, y) = g(x) g(y) for a 1-D profile g on [0, 1): the Gaussian clipped to
// the square (a smooth shading blob whose only discontinuities are where the
// square's edges cut its tails) and the raised-cosine product
// (1 + cos 2 pi x)(1 + cos 2 pi y) / 4 (smooth and periodic: only the
// frequencies |a|, |b| <= 1 carry energy).
class SeparableIntegrand final : public Integrand {
 public:
  static std::unique_ptr<SeparableIntegrand> ClippedGaussian(double centre, double sigma);
  static std::unique_ptr<SeparableIntegrand> CosineProduct();

  std::string name() const override { return name_; }
  double Value(const Point2& p) const override { return Profile(p.x) * Profile(p.y); }
  double Integral() const override { return integral_ * integral_; }
  double SquareIntegral() const override { return square_integral_ * square_integral_; }
  std::complex<double> Fourier(int a, int b) const override;

  // The largest |a| whose 1-D coefficient is known to full accuracy (beyond
  // it Fourier() returns 0 for the Gaussian; the exact variance accounts for
  // the missing energy through SquareIntegral).
  static constexpr int kMaxFrequency = 2048;

 private:
  enum class Kind { kGaussian, kCosine };
  SeparableIntegrand(Kind kind, double centre, double sigma);
  double Profile(double x) const;
  std::complex<double> Coefficient1D(int a) const;

  Kind kind_;
  double centre_ = 0.5, sigma_ = 0.15;
  std::string name_;
  double integral_ = 0.0, square_integral_ = 0.0;
  std::vector<std::complex<double>> coefficients_;  // a = 0 .. kMaxFrequency (Gaussian)
};

// The half-plane {(x - c).n >= 0} clipped to the square, with n the unit
// normal at `normal_deg` and c = (1/2, 1/2) + offset n.
std::unique_ptr<PiecewiseLinearIntegrand> StepEdge(double normal_deg, double offset = 0.0);
// The same edge smoothed into a linear ramp of `width` across it (value 1/2
// on the edge line, 0 and 1 beyond): continuous inside the square.
std::unique_ptr<PiecewiseLinearIntegrand> SmoothedStep(double normal_deg, double width,
                                                       double offset = 0.0);
// The indicator of a convex polygon inside the square.
std::unique_ptr<PiecewiseLinearIntegrand> PolygonIndicator(std::string name, Polygon polygon);
// A linear ramp over the whole square, f = (x + y) / 2: smooth inside, so on
// the torus its only discontinuities are the square's own edges.
std::unique_ptr<PiecewiseLinearIntegrand> SquareBoundaryRamp();

// An integrand from a spec (for command lines and benchmarks):
//   step:DEG[:OFFSET]            smoothstep:DEG[:WIDTH[:OFFSET]] (width 0.1)
//   disk[:R[:CX:CY]] (r 0.3)     triangle      polygon:K[:ROT_DEG] (radius 0.35)
//   gaussian[:SIGMA] (0.15)      product       boundary
StatusOr<std::unique_ptr<Integrand>> MakeIntegrand(const std::string& spec);

// The integrand family the optimized sets are judged on (issue: low-frequency
// floor) for a set aligned to theta: the aligned step, the steps at 0, 90 and
// theta + 45 degrees, the smoothed step at theta, a disk, a triangle, the
// Gaussian and the cosine product. Specs, in that order.
std::vector<std::string> IntegrandFamilySpecs(double theta_deg);

}  // namespace alignset

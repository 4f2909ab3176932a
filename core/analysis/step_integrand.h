#pragma once

#include "core/util/angles.h"
#include "core/util/point_set.h"

namespace alignset {

// The indicator of a half-plane clipped to the unit square: f(p) = 1 where
// (p - c).n >= 0, with n the unit normal at `normal_deg` and c = (1/2, 1/2) +
// offset * n. Its spectrum has its energy along n (plus the square's own
// horizontal and vertical edges once periodized), the integrand the aligned
// sets are made for.
class StepIntegrand {
 public:
  explicit StepIntegrand(double normal_deg, double offset = 0.0);
  double operator()(const Point2& p) const {
    return (p.x - cx_) * n_.x + (p.y - cy_) * n_.y >= 0.0 ? 1.0 : 0.0;
  }
  // The exact integral over [0,1]^2 (area of the clipped half-plane).
  double Integral() const { return integral_; }
  double normal_deg() const { return normal_deg_; }

 private:
  double normal_deg_;
  Vec2 n_;
  double cx_, cy_;
  double integral_;
};

}  // namespace alignset

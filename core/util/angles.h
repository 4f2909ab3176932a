#pragma once

#include <cmath>
#include <numbers>

#include "core/util/directions.h"

namespace alignset {

// Angles are degrees everywhere outside this header. A direction θ names the
// *spectral* direction: the normal of the integrand's discontinuity edge, along
// which its power spectrum has high energy.
inline constexpr double kPi = std::numbers::pi;

inline double DegToRad(double deg) { return deg * (kPi / 180.0); }

// ReduceDirection, ServedDegree, AxialDistance(Deg): core/util/directions.h.

struct Vec2 {
  double x;
  double y;
};

// Unit vector at `deg`, exact at multiples of 90° so that axis-aligned strips
// select exactly the integer rows they should.
inline Vec2 UnitVector(double deg) {
  const double r = ReduceDirection(deg);
  if (r == 0.0) return {1.0, 0.0};
  if (r == 90.0) return {0.0, 1.0};
  const double rad = DegToRad(r);
  return {std::cos(rad), std::sin(rad)};
}

}  // namespace alignset

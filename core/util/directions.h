#pragma once

// The rules every part of alignset shares about directions: how an angle is
// reduced, which whole degree a server serves for it, and how far apart two
// directions are. Installed with the client library as <alignset/directions.h>
// (a renderer applies the same rules as the server), so it includes nothing
// but the standard library.
//
// A direction θ is in degrees and names the *spectral* direction: the normal
// of the integrand's discontinuity edge, along which its power spectrum has
// high energy. Directions are lines, not rays: θ and θ + 180° are one.

#include <algorithm>
#include <cmath>
#include <numbers>

namespace alignset {

// Reduces any finite angle (degrees) to [0, 180).
inline double ReduceDirection(double deg) {
  double r = std::fmod(deg, 180.0);
  if (r < 0.0) r += 180.0;
  if (r >= 180.0) r -= 180.0;
  return r;
}

// The whole degree a server serves for a requested θ: the nearest whole
// degree (ties away from zero), reduced mod 180, as canonicalization
// (core/align) maps a one-direction request to its key.
inline int ServedDegree(double deg) {
  return static_cast<int>(std::lround(ReduceDirection(deg))) % 180;
}

// Axial distance between two directions in degrees, in [0, 90].
inline double AxialDistanceDeg(double a, double b) {
  const double d = std::abs(ReduceDirection(a) - ReduceDirection(b));
  return std::min(d, 180.0 - d);
}

// The same distance for directions in radians, in [0, pi/2].
inline double AxialDistance(double a, double b) {
  const double d = std::fmod(std::fabs(a - b), std::numbers::pi);
  return std::min(d, std::numbers::pi - d);
}

}  // namespace alignset

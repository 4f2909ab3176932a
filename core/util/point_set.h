#pragma once

#include <cstddef>
#include <vector>

namespace alignset {

// A point in the unit torus [0,1)^2. Doubles because the spectrum at the
// highest suppressed frequencies (|v| ~ 1000) needs phases accurate to 1e-9.
struct Point2 {
  double x = 0.0;
  double y = 0.0;
  friend bool operator==(const Point2&, const Point2&) = default;
};

using PointSet = std::vector<Point2>;

// Wraps a coordinate into [0, 1); handles values like -1e-17 whose naive
// `x - floor(x)` rounds to exactly 1.0.
inline double Wrap01(double v) {
  double w = v - static_cast<double>(static_cast<long long>(v));
  if (w < 0.0) w += 1.0;
  if (w >= 1.0) w -= 1.0;
  return w;
}

}  // namespace alignset

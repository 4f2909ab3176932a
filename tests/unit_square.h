#pragma once

// Every point set the project makes lives in the half-open square [0, 1)^2;
// the tests of samplers, alignment and lattices check it the same way.
#include <string>

#include "core/util/point_set.h"

namespace alignset::testing {

// "" when every point of p lies in [0, 1)^2; else the first that does not,
// with its index.
inline std::string OutsideUnitSquare(const PointSet& p) {
  for (size_t i = 0; i < p.size(); ++i) {
    const Point2& q = p[i];
    if (!(q.x >= 0.0 && q.x < 1.0 && q.y >= 0.0 && q.y < 1.0)) {
      return "point " + std::to_string(i) + " (" + std::to_string(q.x) + ", " + std::to_string(q.y) + ")";
    }
  }
  return "";
}

}  // namespace alignset::testing

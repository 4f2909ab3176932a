#pragma once

#include <cmath>
#include <complex>
#include <vector>

#include "core/util/point_set.h"

namespace alignset::test_support {

// ||a - b|| / ||b||: how engines are compared with the direct reference.
inline double RelativeError(const std::vector<std::complex<double>>& a,
                            const std::vector<std::complex<double>>& b) {
  double diff = 0.0, norm = 0.0;
  for (size_t i = 0; i < b.size(); ++i) {
    diff += std::norm(a[i] - b[i]);
    norm += std::norm(b[i]);
  }
  return std::sqrt(diff / norm);
}

inline double RelativeError(const std::vector<Point2>& a, const std::vector<Point2>& b) {
  double diff = 0.0, norm = 0.0;
  for (size_t i = 0; i < b.size(); ++i) {
    const double dx = a[i].x - b[i].x, dy = a[i].y - b[i].y;
    diff += dx * dx + dy * dy;
    norm += b[i].x * b[i].x + b[i].y * b[i].y;
  }
  return std::sqrt(diff / norm);
}

}  // namespace alignset::test_support

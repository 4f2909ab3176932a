#pragma once

// The (0,m,2)-net property in base 2, counted, for the tests of every
// construction that claims it (Owen-scrambled Sobol, aligned nets, the
// served net).
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "core/util/point_set.h"

namespace alignset::testing {

// "" when p holds 2^m points and every elementary interval
// [a/2^k, (a+1)/2^k) x [b/2^(m-k), (b+1)/2^(m-k)) of area 2^-m, for every k,
// holds exactly one of them; else the first place where that fails.
inline std::string NetViolation(const PointSet& p) {
  int m = 0;
  while ((size_t{1} << m) < p.size()) ++m;
  if ((size_t{1} << m) != p.size()) return std::to_string(p.size()) + " points: not a power of two";
  const uint32_t n = 1u << m;
  for (int k = 0; k <= m; ++k) {
    std::vector<int> count(n, 0);
    for (const Point2& q : p) {
      const double a = std::floor(std::ldexp(q.x, k)), b = std::floor(std::ldexp(q.y, m - k));
      if (!(a >= 0.0 && a < (1u << k) && b >= 0.0 && b < (1u << (m - k)))) {
        return "(" + std::to_string(q.x) + ", " + std::to_string(q.y) + ") is outside [0,1)^2";
      }
      ++count[(static_cast<uint32_t>(a) << (m - k)) | static_cast<uint32_t>(b)];
    }
    for (uint32_t c = 0; c < n; ++c) {
      if (count[c] != 1) {
        return std::to_string(n) + " points: " + std::to_string(count[c]) + " in interval " + std::to_string(c) +
               " of shape 2^-" + std::to_string(k) + " x 2^-" + std::to_string(m - k);
      }
    }
  }
  return "";
}

// The same for every power-of-two prefix of p.
inline std::string PrefixNetViolation(const PointSet& p) {
  for (size_t size = 1; size <= p.size(); size *= 2) {
    std::string why = NetViolation(PointSet(p.begin(), p.begin() + size));
    if (!why.empty()) return "prefix of " + std::to_string(size) + ": " + why;
  }
  return "";
}

}  // namespace alignset::testing

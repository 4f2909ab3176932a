#pragma once

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "core/util/hash.h"
#include "core/util/point_set.h"
#include "core/util/status.h"

namespace alignset {

// The largest point count a sampler makes (as the optimizer: kMaxPoints).
inline constexpr uint32_t kMaxSamplerPoints = 1u << 20;

// Refuses N outside [1, kMaxSamplerPoints] with a message naming the sampler.
inline Status CheckSampleCount(const std::string& sampler, uint32_t n) {
  if (n < 1 || n > kMaxSamplerPoints) {
    return Status::InvalidArgument(sampler + ": N must be in [1, " +
                                   std::to_string(kMaxSamplerPoints) + "], got " +
                                   std::to_string(n));
  }
  return Status::Ok();
}

// (i + u) / m, nudged so that floor(v * m) == i holds as computed in double:
// rounding could otherwise put a point that belongs to stratum i on the
// stratum's upper edge (or at 1.0).
inline double InStratum(uint32_t i, double u, uint32_t m) {
  double v = (static_cast<double>(i) + u) / static_cast<double>(m);
  while (v > 0.0 && std::floor(v * m) > i) v = std::nextafter(v, 0.0);
  while (std::floor(v * m) < i) v = std::nextafter(v, 1.0);
  return v;
}

// A uniform random permutation of 0..n-1 (Fisher-Yates, deterministic).
inline std::vector<uint32_t> RandomPermutation(uint32_t n, Pcg32& rng) {
  std::vector<uint32_t> p(n);
  for (uint32_t i = 0; i < n; ++i) p[i] = i;
  for (uint32_t i = n; i > 1; --i) std::swap(p[i - 1], p[rng.Uniform(i)]);
  return p;
}

// A 32-bit fixed-point fraction as a double (exact, and < 1).
inline double FromFixed32(uint32_t v) { return static_cast<double>(v) * 0x1.0p-32; }

// Toroidal squared distance in the unit square.
inline double TorusDistanceSquared(const Point2& a, const Point2& b) {
  double dx = std::abs(a.x - b.x), dy = std::abs(a.y - b.y);
  dx = std::min(dx, 1.0 - dx);
  dy = std::min(dy, 1.0 - dy);
  return dx * dx + dy * dy;
}

// The integer square root when n is a perfect square, else 0.
inline uint32_t ExactSquareRoot(uint32_t n) {
  uint32_t r = static_cast<uint32_t>(std::sqrt(static_cast<double>(n)));
  while (static_cast<uint64_t>(r) * r > n) --r;
  while (static_cast<uint64_t>(r + 1) * (r + 1) <= n) ++r;
  return static_cast<uint64_t>(r) * r == n ? r : 0;
}

}  // namespace alignset

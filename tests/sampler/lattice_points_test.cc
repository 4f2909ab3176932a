// <alignset/lattice_points.h>, the per-pixel points of a served lattice:
// with the shift a realization uses it gives that realization's points bit
// for bit, without a shift the lattice itself, and a pixel's own shifts are
// an unbiased estimator.
#include <alignset/lattice_points.h>

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <numeric>

#include "core/optimize/aligned_lattice.h"
#include "core/util/hash.h"
#include "tests/unit_square.h"

namespace alignset {
namespace {

TEST(LatticePointsHeader, ARealizationsShiftGivesItsPointsBitForBit) {
  for (uint32_t n : {64u, 1000u, 4096u}) {
    for (uint32_t g : {3u, 397u % n, n - 5}) {
      if (std::gcd(g, n) != 1) continue;
      for (uint64_t seed : {0u, 7u, 63u}) {
        EXPECT_EQ(ShiftedLatticePoints(n, g, TentLatticeShift(seed), true), TentLatticePoints(n, g, seed))
            << "N " << n << " g " << g << " seed " << seed;
      }
    }
  }
}

TEST(LatticePointsHeader, WithoutAShiftTheLatticeItself) {
  const uint32_t n = 1024, g = 397;
  const PointSet p = ShiftedLatticePoints(n, g, {0.0, 0.0}, false);
  ASSERT_EQ(p.size(), n);
  for (uint32_t i = 0; i < n; ++i) {
    EXPECT_EQ(p[i].x, static_cast<double>(i) / n);
    EXPECT_EQ(p[i].y, static_cast<double>((uint64_t{i} * g) % n) / n);
  }
  // Folded, every coordinate lies in [0, 1), the fold's 1 included.
  EXPECT_EQ(testing::OutsideUnitSquare(ShiftedLatticePoints(n, g, {0.5, 0.25}, true)), "");
}

// A pixel's own uniform shifts: the mean estimate over many shifts is the
// integral (within 4 standard errors), folded or not.
TEST(LatticePointsHeader, OwnShiftsAreUnbiased) {
  const uint32_t n = 64, g = 19;
  const double exact = (std::exp(1.0) - 1.0) / 3.0;  // integral of e^x y^2
  for (bool folded : {false, true}) {
    const int shifts = 400;
    double sum = 0.0, sum2 = 0.0;
    for (int k = 0; k < shifts; ++k) {
      const uint64_t h = HashCombine(12345, static_cast<uint64_t>(k));
      const Point2 s = {static_cast<double>(h >> 11) * 0x1.0p-53,
                        static_cast<double>(HashCombine(h, 1) >> 11) * 0x1.0p-53};
      double est = 0.0;
      for (const Point2& q : ShiftedLatticePoints(n, g, s, folded)) est += std::exp(q.x) * q.y * q.y;
      est /= n;
      sum += est;
      sum2 += est * est;
    }
    const double mean = sum / shifts, var = sum2 / shifts - mean * mean;
    EXPECT_GT(var, 0.0);
    EXPECT_LT(std::abs(mean - exact), 4.0 * std::sqrt(var / shifts) + 1e-15) << "folded " << folded;
  }
}

}  // namespace
}  // namespace alignset

// The tabulated indicator spectrum against the direct one (IndicatorSpectrum,
// itself held against the general polygon transform): inside and beyond its
// tables, without tables, on frequencies perpendicular to an edge (where the
// vertex difference cancels) and on a polygon with vertices off the square's
// sides.
#include "core/analysis/integer_indicator_spectrum.h"

#include <gtest/gtest.h>

#include <utility>
#include <vector>

#include "core/analysis/lattice_variance.h"
#include "core/util/angles.h"

namespace alignset {
namespace {

std::vector<std::pair<int, int>> Frequencies() {
  std::vector<std::pair<int, int>> h = {{1, 0}, {0, 1}, {-1, 1}, {5, 5}, {-7, 7}, {300, 300},
                                        {40, 13}, {-911, 2}, {3, 1000}, {-1000, 999}};
  for (int a = -60; a <= 60; a += 7) {
    for (int b = 0; b <= 60; b += 5) {
      if (a != 0 || b != 0) h.push_back({a, b});
    }
  }
  return h;
}

void ExpectSame(const Polygon& p, int radius, bool tabulate) {
  const IndicatorSpectrum direct(p);
  const IntegerIndicatorSpectrum table(p, radius, tabulate);
  ASSERT_TRUE(table.Valid());
  for (auto [a, b] : Frequencies()) {
    const double want = direct.Energy(a, b);
    EXPECT_NEAR(table.Energy(a, b), want, 1e-10 * want + 1e-24)
        << "h=(" << a << "," << b << ") radius " << radius << (tabulate ? "" : " untabulated");
  }
}

TEST(IntegerIndicatorSpectrum, MatchesTheDirectSpectrum) {
  // 45.00001: h = (300, 300) is within 1e-4 of perpendicular to the cut, where
  // the series, not the difference, gives the factor.
  for (double deg : {0.0, 10.0, 37.0, 45.0, 45.00001, 90.0, 135.0, 151.3}) {
    for (double offset : {0.0, 0.21, -0.33}) {
      const Vec2 n = UnitVector(deg);
      const Polygon p = ClipHalfPlane(UnitSquarePolygon(), n, 0.5 * (n.x + n.y) + offset);
      ExpectSame(p, 128, true);   // some frequencies beyond the tables
      ExpectSame(p, 1024, true);  // all inside
      ExpectSame(p, 1024, false);
    }
  }
  // Vertices inside the square: both factors of each are tabulated.
  ExpectSame(RegularPolygon({0.4, 0.55}, 0.3, 5, 12.0), 1024, true);
  // The square's corners are on its sides: no table at all.
  EXPECT_EQ(IntegerIndicatorSpectrum(UnitSquarePolygon(), 64).TableBytes(), 0u);
  // A polygon of more vertices than the class keeps is refused, not misread.
  EXPECT_FALSE(IntegerIndicatorSpectrum(RegularPolygon({0.5, 0.5}, 0.4, 20, 0.0), 64).Valid());
}

}  // namespace
}  // namespace alignset

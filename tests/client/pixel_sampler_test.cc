// <alignset/pixel_sampler.h>, steps 3 and 4 of the per-pixel recipe: the
// request carries the construction a renderer asks for, and a pixel's
// points are the served set's own randomization under the pixel's shift:
// the torus shift for an optimized set, the lattice rebuilt with the shift
// before the fold for a tent-lattice (which is what keeps its win on
// smooth functions that are not periodic on the pixel).
#include <alignset/pixel_sampler.h>

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "core/optimize/aligned_lattice.h"
#include "core/sampling/owen_sobol.h"
#include "core/util/hash.h"
#include "tests/unit_square.h"

namespace alignset {
namespace {

AlignedSet Served(PointSet points, const std::string& construction, uint32_t generator) {
  AlignedSet set;
  set.info.n = static_cast<uint32_t>(points.size());
  set.info.construction = construction;
  set.info.lattice_generator = generator;
  set.points = std::move(points);
  return set;
}

TEST(PixelSamplerRecipe, TheRequestCarriesTheConstruction) {
  const SetChoice one{SetChoice::Kind::kOne, 30, 0};
  const SetChoice two{SetChoice::Kind::kTwo, 30, 120};
  EXPECT_EQ(RequestFor(one, 1024)->construction, "");
  const auto lattice = RequestFor(one, 1024, "tent-lattice");
  ASSERT_TRUE(lattice.has_value());
  EXPECT_EQ(lattice->construction, "tent-lattice");
  EXPECT_EQ(lattice->n, 1024u);
  EXPECT_EQ(lattice->directions_deg, std::vector<double>{30.0});
  EXPECT_EQ(RequestFor(two, 256, "lattice")->directions_deg, (std::vector<double>{30.0, 120.0}));
  EXPECT_FALSE(RequestFor(SetChoice{}, 1024, "lattice").has_value());
}

TEST(PixelSamplerRecipe, AnOptimizedSetIsShiftedOnTheTorus) {
  const AlignedSet set = Served(OwenScrambledSobol(256, 9), "optimized", 0);
  const Point2 s = PixelShift(3, 17, 40);
  const PointSet p = PixelPoints(set, s);
  ASSERT_EQ(p.size(), set.points.size());
  for (size_t i = 0; i < p.size(); ++i) EXPECT_EQ(p[i], ShiftPoint(set.points[i], s)) << i;
  EXPECT_EQ(testing::OutsideUnitSquare(p), "");
}

TEST(PixelSamplerRecipe, ALatticeIsRebuiltFromItsGeneratorUnderThePixelsShift) {
  const uint32_t n = 1024, g = 397;
  const Point2 s = PixelShift(3, 17, 40);
  EXPECT_EQ(PixelPoints(Served(LatticePoints(n, g, 5, false), "lattice", g), s),
            ShiftedLatticePoints(n, g, s, false));
  EXPECT_EQ(PixelPoints(Served(TentLatticePoints(n, g, 5), "tent-lattice", g), s),
            ShiftedLatticePoints(n, g, s, true));
  // Under the realization's own shift, the served tent-lattice itself.
  const PointSet served = TentLatticePoints(n, g, 5);
  EXPECT_EQ(PixelPoints(Served(served, "tent-lattice", g), TentLatticeShift(5)), served);
}

TEST(PixelSamplerRecipe, WithoutAGeneratorALatticeIsShiftedOnTheTorus) {
  const PointSet served = TentLatticePoints(256, 19, 2);
  const Point2 s = PixelShift(1, 2, 3);
  const PointSet p = PixelPoints(Served(served, "tent-lattice", 0), s);
  for (size_t i = 0; i < p.size(); ++i) EXPECT_EQ(p[i], ShiftPoint(served[i], s)) << i;
}

// Why the recipe rebuilds a tent-lattice: over many pixels' shifts both
// randomizations are unbiased on a smooth function that is not periodic on
// the pixel (e^x y^2), but the shift before the fold has far less variance
// than a torus shift of the served, folded points.
TEST(PixelSamplerRecipe, ATentLatticesOwnShiftBeatsATorusShiftOnSmoothShading) {
  const uint32_t n = 256, g = 99;
  const double exact = (std::exp(1.0) - 1.0) / 3.0;
  const AlignedSet with_g = Served(TentLatticePoints(n, g, 0), "tent-lattice", g);
  const AlignedSet without_g = Served(with_g.points, "tent-lattice", 0);
  auto stats = [&](const AlignedSet& set) {
    const int pixels = 400;
    double sum = 0.0, sum2 = 0.0;
    for (int k = 0; k < pixels; ++k) {
      double est = 0.0;
      for (const Point2& q : PixelPoints(set, PixelShift(77, k, 0))) est += std::exp(q.x) * q.y * q.y;
      est /= n;
      sum += est;
      sum2 += est * est;
    }
    const double mean = sum / pixels;
    const double var = (sum2 - pixels * mean * mean) / (pixels - 1);
    return std::pair<double, double>{mean, var};
  };
  const auto [mean_g, var_g] = stats(with_g);
  const auto [mean_0, var_0] = stats(without_g);
  EXPECT_LT(std::abs(mean_g - exact), 4.0 * std::sqrt(var_g / 400) + 1e-15);
  EXPECT_LT(std::abs(mean_0 - exact), 4.0 * std::sqrt(var_0 / 400));
  EXPECT_LT(5.0 * var_g, var_0) << "own shift " << var_g << ", torus shift " << var_0;
}

}  // namespace
}  // namespace alignset

// The key lineage: every key of each canonical space reaches a root in a
// bounded number of steps, each step moves one direction by one degree (a quarter or half degree on the quarter grid),
// the parent's set aligned by the step's ops is dark along the neighbouring
// directions, and the whole-degree keys have the same lineage on both grids.
#include "core/align/key_lineage.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace alignset {
namespace {

double AxialGap(double a, double b) {
  double d = std::fmod(std::fabs(a - b), 180.0);
  return std::min(d, 180.0 - d);
}

// The directions the parent's set serves once aligned by `ops`, sorted.
std::vector<double> ServedByParent(const LineageParent& p) {
  std::vector<double> d = {MapDirection(Phi1Degrees(p.parent), p.ops)};
  if (p.parent.count == 2) d.push_back(MapDirection(Phi2Degrees(p.parent), p.ops));
  return d;
}

// True when the parent's aligned directions match the child's with exactly
// one of them moved by `step` degrees (for two directions, in some pairing).
bool OneStepApart(const CanonicalDirections& child, const LineageParent& p, double step) {
  const std::vector<double> served = ServedByParent(p);
  if (child.count == 1) return std::fabs(AxialGap(served[0], Phi1Degrees(child)) - step) < 1e-9;
  const double c1 = Phi1Degrees(child), c2 = Phi2Degrees(child);
  for (int swap = 0; swap < 2; ++swap) {
    const double s1 = served[swap], s2 = served[1 - swap];
    const double g1 = AxialGap(s1, c1), g2 = AxialGap(s2, c2);
    if ((std::fabs(g1 - step) < 1e-9 && g2 < 1e-9) || (std::fabs(g2 - step) < 1e-9 && g1 < 1e-9)) {
      return true;
    }
  }
  return false;
}

struct Space {
  int count;
  AngleGrid grid;
  int max_depth;
  size_t roots;
};

TEST(KeyLineage, EveryKeyReachesARootInAFewShortSteps) {
  for (const Space& space : {Space{1, AngleGrid::kWholeDegree, 3, 7}, Space{2, AngleGrid::kWholeDegree, 3, 226},
                             Space{1, AngleGrid::kQuarterDegree, 4, 7}}) {
    const size_t size = CanonicalKeyCount(space.count, space.grid);
    size_t roots = 0;
    int deepest = 0;
    for (size_t i = 0; i < size; ++i) {
      const CanonicalDirections key = CanonicalKeyAt(space.count, i, space.grid);
      const int depth = LineageDepth(key);
      ASSERT_GE(depth, 0) << ToString(key);
      deepest = std::max(deepest, depth);
      const auto parent = WarmParent(key);
      if (!parent) {
        EXPECT_EQ(depth, 0) << ToString(key);
        ++roots;
        continue;
      }
      // The parent is a canonical key of the same space, one step nearer.
      EXPECT_TRUE(CanonicalKeyIndex(parent->parent, space.grid).ok()) << ToString(parent->parent);
      EXPECT_EQ(LineageDepth(parent->parent), depth - 1) << ToString(key);
      const double step = key.phi1_quarter == 2 ? 0.5 : key.phi1_quarter != 0 ? 0.25 : 1.0;
      EXPECT_TRUE(OneStepApart(key, *parent, step))
          << ToString(key) << " from " << ToString(parent->parent) << " by " << ToString(parent->ops);
    }
    EXPECT_EQ(roots, space.roots);
    EXPECT_EQ(deepest, space.max_depth);
    EXPECT_EQ(MaxLineageDepth(space.count, space.grid), space.max_depth);
  }
}

TEST(KeyLineage, WholeDegreeKeysHaveOneLineageOnBothGrids) {
  for (int phi = 0; phi <= 45; ++phi) {
    const CanonicalDirections whole = CanonicalKeyAt(1, static_cast<size_t>(phi));
    const CanonicalDirections quarter = CanonicalKeyAt(1, static_cast<size_t>(4 * phi), AngleGrid::kQuarterDegree);
    ASSERT_EQ(whole, quarter);
    const auto a = WarmParent(whole);
    const auto b = WarmParent(quarter);
    ASSERT_EQ(a.has_value(), b.has_value());
    if (a) {
      EXPECT_EQ(a->parent, b->parent);
      EXPECT_EQ(a->ops, b->ops);
      EXPECT_EQ(a->parent.phi1_quarter, 0) << "a whole-degree key's lineage stays on whole degrees";
    }
  }
}

TEST(KeyLineage, NonCanonicalKeysHaveNoLineage) {
  EXPECT_FALSE(WarmParent({3, 10, 20, 0}).has_value());
  EXPECT_FALSE(WarmParent({1, 50, 50, 0}).has_value());
  EXPECT_FALSE(WarmParent({2, 60, 10, 0}).has_value());  // not its orbit's representative
  EXPECT_EQ(LineageDepth({2, 60, 10, 0}), -1);
  EXPECT_EQ(LineageDepth({1, 45, 45, 2}), -1);
}

}  // namespace
}  // namespace alignset

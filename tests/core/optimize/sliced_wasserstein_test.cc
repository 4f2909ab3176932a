#include "core/optimize/sliced_wasserstein.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "core/util/angles.h"

namespace alignset {
namespace {

// Sorted projections of a dense uniform grid approximate the projection's
// quantiles; Eq. 17 (folded) must agree with them.
std::vector<double> GridQuantiles(uint32_t n, double deg) {
  const int m = 1000;  // 10^6 grid points
  const Vec2 d{std::cos(DegToRad(deg)), std::sin(DegToRad(deg))};
  std::vector<double> proj;
  proj.reserve(m * m);
  for (int i = 0; i < m; ++i) {
    for (int j = 0; j < m; ++j) proj.push_back(((i + 0.5) / m) * d.x + ((j + 0.5) / m) * d.y);
  }
  std::sort(proj.begin(), proj.end());
  std::vector<double> q(n);
  for (uint32_t i = 0; i < n; ++i) {
    q[i] = proj[static_cast<size_t>((i + 0.5) / n * proj.size())];
  }
  return q;
}

TEST(SlicedWasserstein, TargetsMatchGridQuantilesInAllQuadrants) {
  for (double deg : {0.0, 10.0, 30.0, 45.0, 60.0, 90.0, 100.0, 120.0, 135.0, 170.0}) {
    const std::vector<double> t = WassersteinTargets(200, deg);
    const std::vector<double> q = GridQuantiles(200, deg);
    for (size_t i = 0; i < t.size(); ++i) {
      ASSERT_NEAR(t[i], q[i], 2e-3) << "deg " << deg << " i " << i;
    }
  }
}

TEST(SlicedWasserstein, UnfoldedEquationIsWrongOutsideZeroTo45) {
  // Eq. 17 with the raw cos/sin of 120° (c < 0, so every u falls in its linear
  // branch) is off by about 0.7 near the ends; the folded version is what
  // the targets use, and it equals the 30° law.
  const double c = std::cos(DegToRad(120)), s = std::sin(DegToRad(120));
  double worst = 0;
  for (int i = -50; i <= 50; ++i) {
    const double u = i / 100.0;
    const double raw = std::abs(u) < (c - s) / (2 * c)
                           ? u * c
                           : (u > 0 ? 1 : -1) * ((c + s) / 2 - std::sqrt(std::max(0.0, 2 * s * c * (0.5 - std::abs(u)))));
    worst = std::max(worst, std::abs(raw - ProjectionInverseCdf(u, 120)));
    EXPECT_DOUBLE_EQ(ProjectionInverseCdf(u, 120), ProjectionInverseCdf(u, 30));
  }
  EXPECT_GT(worst, 0.6);
}

TEST(SlicedWasserstein, InverseCdfIsMonotoneAndSymmetric) {
  for (double deg : {0.0, 20.0, 45.0, 110.0}) {
    double prev = -1e9;
    for (int i = -50; i <= 50; ++i) {
      const double u = i / 100.0;
      const double v = ProjectionInverseCdf(u, deg);
      EXPECT_GE(v, prev);
      EXPECT_NEAR(v, -ProjectionInverseCdf(-u, deg), 1e-12);
      prev = v;
    }
  }
}

TEST(SlicedWasserstein, WarmOrderGivesExactlyTheFreshResult) {
  // The cached order from a previous call must not change the result: small
  // moves (the insertion-sort path), wraps across the edge, ties, and a
  // complete reshuffle (the fallback path) all agree bit for bit.
  const uint32_t n = 2000;
  PointSet a;
  for (uint32_t i = 0; i < n; ++i) a.push_back({((i * 7919) % n + 0.5) / n, ((i * 104729) % n + 0.5) / n});
  const std::vector<double> dirs = {0.0, 90.0, 30.0};
  const SlicedWasserstein warm(n, dirs);
  std::vector<Point2> g_warm, g_fresh;
  warm.Evaluate(a, &g_warm);
  PointSet small = a, shuffled = a;
  for (uint32_t i = 0; i < n; ++i) {
    small[i].x = Wrap01(small[i].x + 1e-4 * ((i % 7) - 3.0));
    shuffled[i] = a[(i * 31) % n];
  }
  small[5].x = 0.99999;  // ties and a wrap
  small[6].x = 0.99999;
  small[7].x = Wrap01(a[7].x + 0.5);
  for (const PointSet* p : {&small, &shuffled, &a}) {
    const double lw = warm.Evaluate(*p, &g_warm);
    const double lf = SlicedWasserstein(n, dirs).Evaluate(*p, &g_fresh);
    EXPECT_EQ(lw, lf);
    EXPECT_EQ(g_warm, g_fresh);
  }
}

TEST(SlicedWasserstein, PerfectStratificationHasZeroAxisLoss) {
  // N points on the diagonal of an N x N grid: each axis projection is exactly
  // the target quantiles.
  const uint32_t n = 64;
  PointSet pts;
  for (uint32_t i = 0; i < n; ++i) pts.push_back({(i + 0.5) / n, (i * 37 % n + 0.5) / n});
  const SlicedWasserstein sw(n, {0.0, 90.0});
  EXPECT_NEAR(sw.Evaluate(pts, nullptr), 0.0, 1e-30);
  const SlicedWasserstein oblique(n, {0.0, 90.0, 30.0});
  EXPECT_GT(oblique.Evaluate(pts, nullptr), 0.0);
}

}  // namespace
}  // namespace alignset

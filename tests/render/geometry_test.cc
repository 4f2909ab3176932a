#include "render/geometry.h"

#include <gtest/gtest.h>

#include <cmath>

#include "render/pixel_integrand.h"
#include "core/util/hash.h"

namespace alignset::render {
namespace {

Polygon Square(double x0, double y0, double x1, double y1) {
  return {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}};
}

Polygon RegularPolygon(V2 c, double r, int k, double phase) {
  Polygon p;
  for (int i = 0; i < k; ++i) {
    const double a = phase + 2 * M_PI * i / k;
    p.push_back({c.x + r * std::cos(a), c.y + r * std::sin(a)});
  }
  return p;
}

Polygon RandomConvex(Pcg32& rng, V2 c, double r) {
  // Points on a circle at sorted random angles are a convex polygon.
  std::vector<double> a;
  const int k = 3 + static_cast<int>(rng.Uniform(5));
  for (int i = 0; i < k; ++i) a.push_back(2 * M_PI * rng.NextDouble());
  std::sort(a.begin(), a.end());
  Polygon p;
  for (double t : a) p.push_back({c.x + r * std::cos(t), c.y + r * std::sin(t)});
  return p;
}

// Midpoint quadrature of f over the polygon on an m x m grid of its bounds.
double Quadrature(const Polygon& p, const Linear& f, int m) {
  const Box b = Bounds(p);
  const double hx = (b.x1 - b.x0) / m, hy = (b.y1 - b.y0) / m;
  double sum = 0.0;
  for (int j = 0; j < m; ++j) {
    for (int i = 0; i < m; ++i) {
      const V2 q = {b.x0 + (i + 0.5) * hx, b.y0 + (j + 0.5) * hy};
      if (Contains(p, q)) sum += f(q);
    }
  }
  return sum * hx * hy;
}

TEST(Geometry, AreasOfKnownShapes) {
  EXPECT_DOUBLE_EQ(Area(Square(0, 0, 1, 1)), 1.0);
  EXPECT_DOUBLE_EQ(Area(Polygon{{0, 0}, {2, 0}, {0, 3}}), 3.0);
  EXPECT_DOUBLE_EQ(Area(Polygon{{0, 0}, {0, 3}, {2, 0}}), -3.0);  // clockwise
  const int k = 64;
  EXPECT_NEAR(Area(RegularPolygon({5, 7}, 2.0, k, 0.3)), 0.5 * k * 4.0 * std::sin(2 * M_PI / k), 1e-12);
}

TEST(Geometry, LinearIntegralMatchesTheCentroidRuleAndQuadrature) {
  Pcg32 rng(11);
  for (int trial = 0; trial < 20; ++trial) {
    const Polygon p = RandomConvex(rng, {40 + rng.NextDouble(), 17 + rng.NextDouble()}, 0.3 + rng.NextDouble());
    const Linear f{rng.NextDouble() - 0.5, 2 * rng.NextDouble() - 1, 2 * rng.NextDouble() - 1};
    // Independent closed form: a fan of triangles, each area x f(centroid).
    double fan = 0.0;
    for (size_t i = 1; i + 1 < p.size(); ++i) {
      const Polygon t = {p[0], p[i], p[i + 1]};
      const V2 c = (1.0 / 3.0) * (p[0] + p[i] + p[i + 1]);
      fan += Area(t) * f(c);
    }
    EXPECT_NEAR(Integral(p, f), fan, 1e-12 * (1 + std::abs(fan)));
    EXPECT_NEAR(Integral(p, f), Quadrature(p, f, 1500), 2e-3 * Area(p) * (1 + std::abs(f(p[0]))));
  }
}

TEST(Geometry, ClippingGivesKnownAreas) {
  const Polygon unit = Square(0, 0, 1, 1);
  EXPECT_NEAR(Area(ClipHalfPlane(unit, {1, 1}, 1.0)), 0.5, 1e-15);
  EXPECT_NEAR(Area(ClipConvex(unit, Square(0.5, 0.5, 1.5, 1.5))), 0.25, 1e-15);
  // The unit square and its 45° turn about the centre meet in a regular
  // octagon of area 2 (sqrt 2 - 1).
  const Polygon turned = RegularPolygon({0.5, 0.5}, std::sqrt(0.5), 4, 0.0);
  EXPECT_NEAR(Area(ClipConvex(unit, turned)), 2 * (std::sqrt(2.0) - 1), 1e-14);
  EXPECT_NEAR(Area(ClipRect(turned, 0, 0, 1, 1)), 2 * (std::sqrt(2.0) - 1), 1e-14);
  EXPECT_TRUE(ClipConvex(unit, Square(2, 2, 3, 3)).empty());
}

TEST(Geometry, SubtractionPartitionsTheDifference) {
  Pcg32 rng(5);
  for (int trial = 0; trial < 50; ++trial) {
    const Polygon a = RandomConvex(rng, {0.5, 0.5}, 0.4);
    const Polygon b = RandomConvex(rng, {0.3 + 0.4 * rng.NextDouble(), 0.3 + 0.4 * rng.NextDouble()}, 0.3);
    const std::vector<Polygon> pieces = SubtractConvex(a, b, 0.0);
    double sum = Area(ClipConvex(a, b));
    for (size_t i = 0; i < pieces.size(); ++i) {
      sum += Area(pieces[i]);
      EXPECT_NEAR(Area(ClipConvex(pieces[i], b)), 0.0, 1e-14);  // outside b
      for (size_t j = 0; j < i; ++j) EXPECT_NEAR(Area(ClipConvex(pieces[i], pieces[j])), 0.0, 1e-14);
    }
    EXPECT_NEAR(sum, Area(a), 1e-14);
  }
}

TEST(Geometry, SegmentClippingMatchesPointTests) {
  Pcg32 rng(8);
  for (int trial = 0; trial < 30; ++trial) {
    const Polygon p = RandomConvex(rng, {0.5, 0.5}, 0.35);
    const V2 a = {rng.NextDouble(), rng.NextDouble()}, b = {rng.NextDouble(), rng.NextDouble()};
    double t0 = 0, t1 = 0;
    const bool hit = ClipSegment(p, a, b, &t0, &t1);
    const int m = 20000;
    int inside = 0;
    for (int i = 0; i < m; ++i) inside += Contains(p, a + ((i + 0.5) / m) * (b - a));
    EXPECT_NEAR(hit ? t1 - t0 : 0.0, double(inside) / m, 2.0 / m);
  }
}

TEST(Geometry, FlattenGivesTheFrontmostShapeEverywhere) {
  Pcg32 rng(21);
  std::vector<ShadedPolygon> shapes;
  for (int i = 0; i < 8; ++i) {
    shapes.push_back({RandomConvex(rng, {0.2 + 0.6 * rng.NextDouble(), 0.2 + 0.6 * rng.NextDouble()}, 0.25),
                      Linear{double(i + 1), 0.0, 0.0}});
  }
  const std::vector<Fragment> frags = Flatten(shapes, 0.0);
  for (int j = 0; j < 200; ++j) {
    for (int i = 0; i < 200; ++i) {
      const V2 q = {(i + 0.37) / 200, (j + 0.61) / 200};
      double want = 0.0;
      for (const ShadedPolygon& s : shapes) {
        if (Contains(s.polygon, q)) {
          want = s.shade.c;
          break;
        }
      }
      int owners = 0;
      double got = 0.0;
      for (const Fragment& f : frags) {
        if (Contains(f.polygon, q)) {
          ++owners;
          got = f.shade.c;
        }
      }
      ASSERT_LE(owners, 1) << q.x << "," << q.y;  // disjoint (off a measure-zero set)
      ASSERT_EQ(got, want) << q.x << "," << q.y;
    }
  }
}

}  // namespace
}  // namespace alignset::render

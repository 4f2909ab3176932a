#include "core/analysis/convex_polygon.h"

#include <cmath>

namespace alignset {

Polygon UnitSquarePolygon() { return {{0, 0}, {1, 0}, {1, 1}, {0, 1}}; }

Polygon ClipHalfPlane(const Polygon& polygon, Vec2 n, double c) {
  Polygon out;
  const size_t k = polygon.size();
  auto side = [&](const Vec2& p) { return n.x * p.x + n.y * p.y - c; };
  for (size_t i = 0; i < k; ++i) {
    const Vec2& a = polygon[i];
    const Vec2& b = polygon[(i + 1) % k];
    const double sa = side(a), sb = side(b);
    if (sa >= 0) out.push_back(a);
    if ((sa >= 0) != (sb >= 0)) {
      const double t = sa / (sa - sb);
      out.push_back({a.x + t * (b.x - a.x), a.y + t * (b.y - a.y)});
    }
  }
  // A cut through a vertex or along an edge leaves a sliver of zero area:
  // it integrates to nothing, but keep the contract "empty when clipped away".
  if (out.size() < 3 || std::abs(SignedArea(out)) == 0.0) out.clear();
  return out;
}

double SignedArea(const Polygon& polygon) {
  double twice = 0.0;
  const size_t k = polygon.size();
  for (size_t i = 0; i < k; ++i) {
    const Vec2& a = polygon[i];
    const Vec2& b = polygon[(i + 1) % k];
    twice += a.x * b.y - a.y * b.x;
  }
  return 0.5 * twice;
}

bool ContainsPoint(const Polygon& polygon, Vec2 p) {
  const size_t k = polygon.size();
  if (k < 3) return false;
  for (size_t i = 0; i < k; ++i) {
    const Vec2& a = polygon[i];
    const Vec2& b = polygon[(i + 1) % k];
    const double cross = (b.x - a.x) * (p.y - a.y) - (b.y - a.y) * (p.x - a.x);
    if (cross < -1e-12) return false;
  }
  return true;
}

namespace {

// Sums fn(triangle area, vertices) over a fan from the first vertex.
template <typename Fn>
double OverFan(const Polygon& polygon, Fn fn) {
  double sum = 0.0;
  for (size_t i = 1; i + 1 < polygon.size(); ++i) {
    const Vec2& p0 = polygon[0];
    const Vec2& p1 = polygon[i];
    const Vec2& p2 = polygon[i + 1];
    const double area =
        0.5 * ((p1.x - p0.x) * (p2.y - p0.y) - (p2.x - p0.x) * (p1.y - p0.y));
    sum += fn(area, p0, p1, p2);
  }
  return sum;
}

Vec2 Mid(const Vec2& a, const Vec2& b) { return {0.5 * (a.x + b.x), 0.5 * (a.y + b.y)}; }

}  // namespace

double IntegrateLinear(const Polygon& polygon, const LinearFunction& h) {
  return OverFan(polygon, [&](double area, const Vec2& p0, const Vec2& p1, const Vec2& p2) {
    const Vec2 centroid = {(p0.x + p1.x + p2.x) / 3.0, (p0.y + p1.y + p2.y) / 3.0};
    return area * h(centroid);
  });
}

double IntegrateLinearSquared(const Polygon& polygon, const LinearFunction& h) {
  // The edge-midpoint rule integrates every quadratic exactly on a triangle.
  return OverFan(polygon, [&](double area, const Vec2& p0, const Vec2& p1, const Vec2& p2) {
    const double m01 = h(Mid(p0, p1)), m12 = h(Mid(p1, p2)), m20 = h(Mid(p2, p0));
    return area * (m01 * m01 + m12 * m12 + m20 * m20) / 3.0;
  });
}

Polygon RegularPolygon(Vec2 centre, double radius, int k, double rotation_deg) {
  Polygon p;
  for (int i = 0; i < k; ++i) {
    const double t = DegToRad(rotation_deg) + 2.0 * kPi * i / k;
    p.push_back({centre.x + radius * std::cos(t), centre.y + radius * std::sin(t)});
  }
  return p;
}

}  // namespace alignset

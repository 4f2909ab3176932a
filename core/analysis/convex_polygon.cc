#include "core/analysis/convex_polygon.h"

#include <algorithm>
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

Polygon PolygonWithEdgeNormals(std::vector<double> normals_deg, double size) {
  for (double& d : normals_deg) d = ReduceDirection(d);
  std::sort(normals_deg.begin(), normals_deg.end());
  for (size_t i = 1; i < normals_deg.size(); ++i) {
    if (normals_deg[i] - normals_deg[i - 1] < 1e-9) return {};
  }
  if (!normals_deg.empty() && normals_deg.front() + 180.0 - normals_deg.back() < 1e-9) return {};
  std::vector<double> outward;
  for (size_t i = 0; i < normals_deg.size(); ++i) {
    outward.push_back(normals_deg[i] + (i % 2 == 1 ? 180.0 : 0.0));
  }
  std::sort(outward.begin(), outward.end());
  const size_t k = outward.size();
  if (k < 3) return {};
  for (size_t i = 0; i < k; ++i) {
    const double next = i + 1 < k ? outward[i + 1] : outward[0] + 360.0;
    const double gap = next - outward[i];
    if (!(gap > 1e-9 && gap < 180.0 - 1e-9)) return {};
  }
  // Tangent lines n_i.x = 1 of the unit circle; consecutive ones meet at a
  // vertex (Cramer's rule), counter-clockwise as the normals turn.
  Polygon p;
  for (size_t i = 0; i < k; ++i) {
    // Not UnitVector: that reduces to a line's direction, and these are rays.
    const double ta = DegToRad(outward[i]), tb = DegToRad(outward[(i + 1) % k]);
    const Vec2 a = {std::cos(ta), std::sin(ta)};
    const Vec2 b = {std::cos(tb), std::sin(tb)};
    const double det = a.x * b.y - a.y * b.x;
    p.push_back({(b.y - a.y) / det, (a.x - b.x) / det});
  }
  double lo_x = p[0].x, hi_x = p[0].x, lo_y = p[0].y, hi_y = p[0].y;
  for (const Vec2& v : p) {
    lo_x = std::min(lo_x, v.x);
    hi_x = std::max(hi_x, v.x);
    lo_y = std::min(lo_y, v.y);
    hi_y = std::max(hi_y, v.y);
  }
  const double scale = size / std::max(hi_x - lo_x, hi_y - lo_y);
  const Vec2 mid = {0.5 * (lo_x + hi_x), 0.5 * (lo_y + hi_y)};
  for (Vec2& v : p) v = {0.5 + (v.x - mid.x) * scale, 0.5 + (v.y - mid.y) * scale};
  return p;
}

}  // namespace alignset

#include "render/geometry.h"

#include <algorithm>

namespace alignset::render {
namespace {
constexpr double kSameVertex2 = 1e-24;  // squared distance below which two vertices are one
inline double DistanceSquared(V2 a, V2 b) { return Dot(a - b, a - b); }
}  // namespace

double Area(const Polygon& p) {
  if (p.size() < 3) return 0.0;
  double a = 0.0;
  for (size_t i = 0, n = p.size(); i < n; ++i) a += Cross(p[i], p[(i + 1) % n]);
  return 0.5 * a;
}

double Integral(const Polygon& p, const Linear& f) {
  if (p.size() < 3) return 0.0;
  // Moments about the first vertex keep the sums well conditioned for small
  // polygons far from the origin: f(q) = f(o) + g.(q - o).
  const V2 o = p[0];
  double a2 = 0.0, mx6 = 0.0, my6 = 0.0;
  for (size_t i = 0, n = p.size(); i < n; ++i) {
    const V2 u = p[i] - o, v = p[(i + 1) % n] - o;
    const double c = Cross(u, v);
    a2 += c;
    mx6 += (u.x + v.x) * c;
    my6 += (u.y + v.y) * c;
  }
  return f(o) * 0.5 * a2 + f.gx * mx6 / 6.0 + f.gy * my6 / 6.0;
}

Polygon ClipHalfPlane(const Polygon& p, V2 n, double d) {
  Polygon out;
  const size_t count = p.size();
  if (count < 3) return out;
  out.reserve(count + 1);
  for (size_t i = 0; i < count; ++i) {
    const V2 a = p[i], b = p[(i + 1) % count];
    const double da = Dot(n, a) - d, db = Dot(n, b) - d;
    if (da <= 0.0) out.push_back(a);
    if ((da < 0.0 && db > 0.0) || (da > 0.0 && db < 0.0)) {
      const double t = da / (da - db);
      out.push_back(a + t * (b - a));
    }
  }
  // Drop vertices that coincide with their predecessor to rounding: an edge
  // of length ~1e-16 has an arbitrary direction, and Contains and
  // ClipSegment, which trust every edge's direction, would misjudge points
  // far from it (seen at the centre of a fan of thin triangles).
  Polygon clean;
  clean.reserve(out.size());
  for (const V2& q : out) {
    if (!clean.empty() && DistanceSquared(clean.back(), q) < kSameVertex2) continue;
    clean.push_back(q);
  }
  while (clean.size() > 1 && DistanceSquared(clean.front(), clean.back()) < kSameVertex2) clean.pop_back();
  if (clean.size() < 3) clean.clear();
  return clean;
}

namespace {
// The inside of the counter-clockwise edge a -> b is its left side:
// Dot(n, q) <= Dot(n, a) with n = (e.y, -e.x).
inline void EdgeHalfPlane(V2 a, V2 b, V2* n, double* d) {
  const V2 e = b - a;
  *n = {e.y, -e.x};
  *d = Dot(*n, a);
}
}  // namespace

Polygon ClipConvex(const Polygon& p, const Polygon& clip) {
  Polygon out = p;
  for (size_t i = 0, n = clip.size(); i < n && out.size() >= 3; ++i) {
    V2 normal;
    double d;
    EdgeHalfPlane(clip[i], clip[(i + 1) % n], &normal, &d);
    out = ClipHalfPlane(out, normal, d);
  }
  return out;
}

Polygon ClipRect(const Polygon& p, double x0, double y0, double x1, double y1) {
  Polygon out = ClipHalfPlane(p, {-1, 0}, -x0);
  out = ClipHalfPlane(out, {1, 0}, x1);
  out = ClipHalfPlane(out, {0, -1}, -y0);
  return ClipHalfPlane(out, {0, 1}, y1);
}

std::vector<Polygon> SubtractConvex(const Polygon& a, const Polygon& b, double min_area) {
  std::vector<Polygon> pieces;
  Polygon rest = a;
  for (size_t i = 0, n = b.size(); i < n && rest.size() >= 3; ++i) {
    V2 normal;
    double d;
    EdgeHalfPlane(b[i], b[(i + 1) % n], &normal, &d);
    Polygon out = ClipHalfPlane(rest, -1.0 * normal, -d);
    if (out.size() >= 3 && Area(out) >= min_area) pieces.push_back(std::move(out));
    rest = ClipHalfPlane(rest, normal, d);
  }
  return pieces;
}

bool Contains(const Polygon& p, V2 q) {
  const size_t n = p.size();
  if (n < 3) return false;
  for (size_t i = 0; i < n; ++i) {
    const V2 e = p[(i + 1) % n] - p[i];
    if (Dot(e, e) < kSameVertex2) continue;  // no direction to trust
    if (Cross(e, q - p[i]) < 0.0) return false;
  }
  return true;
}

bool ClipSegment(const Polygon& p, V2 a, V2 b, double* t0, double* t1) {
  double lo = 0.0, hi = 1.0;
  const size_t n = p.size();
  if (n < 3) return false;
  const V2 dir = b - a;
  for (size_t i = 0; i < n; ++i) {
    V2 normal;
    double d;
    EdgeHalfPlane(p[i], p[(i + 1) % n], &normal, &d);
    if (Dot(normal, normal) < kSameVertex2) continue;  // no direction to trust
    const double num = d - Dot(normal, a);
    const double den = Dot(normal, dir);
    if (den == 0.0) {
      if (num < 0.0) return false;
      continue;
    }
    const double t = num / den;
    if (den > 0.0) {
      hi = std::min(hi, t);
    } else {
      lo = std::max(lo, t);
    }
    if (hi <= lo) return false;
  }
  *t0 = lo;
  *t1 = hi;
  return true;
}

Box Bounds(const Polygon& p) {
  Box b{1e300, 1e300, -1e300, -1e300};
  for (const V2& q : p) {
    b.x0 = std::min(b.x0, q.x);
    b.y0 = std::min(b.y0, q.y);
    b.x1 = std::max(b.x1, q.x);
    b.y1 = std::max(b.y1, q.y);
  }
  return b;
}

Polygon MakeCounterClockwise(Polygon p) {
  if (Area(p) < 0.0) std::reverse(p.begin(), p.end());
  return p;
}

}  // namespace alignset::render

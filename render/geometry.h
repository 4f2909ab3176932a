#pragma once

// Exact 2-D geometry for the renderer's references: convex polygons, their
// clipping and differences, and closed-form integrals of linear functions
// over polygons and along segments. Written by hand because no Debian package
// gives exact (non-sampled) integrals of a linear function over a clipped
// polygon; the pieces are small and each is tested against an independent
// computation (tests/render/geometry_test.cc).

#include <cmath>
#include <vector>

namespace alignset::render {

struct V2 {
  double x = 0.0;
  double y = 0.0;
};
inline V2 operator+(V2 a, V2 b) { return {a.x + b.x, a.y + b.y}; }
inline V2 operator-(V2 a, V2 b) { return {a.x - b.x, a.y - b.y}; }
inline V2 operator*(double s, V2 a) { return {s * a.x, s * a.y}; }
inline double Dot(V2 a, V2 b) { return a.x * b.x + a.y * b.y; }
inline double Cross(V2 a, V2 b) { return a.x * b.y - a.y * b.x; }

// A convex polygon, vertices counter-clockwise, no repeated closing vertex.
// Fewer than three vertices is the empty polygon.
using Polygon = std::vector<V2>;

// f(p) = c + gx * p.x + gy * p.y: a flat fill (gx = gy = 0) or a linear
// colour gradient.
struct Linear {
  double c = 0.0;
  double gx = 0.0;
  double gy = 0.0;
  double operator()(V2 p) const { return c + gx * p.x + gy * p.y; }
  // The same function in coordinates q = (p - origin) / scale, i.e.
  // g(q) = f(origin + scale * q).
  Linear InLocal(V2 origin, double scale) const {
    return {(*this)(origin), gx * scale, gy * scale};
  }
};

// Signed area (positive for counter-clockwise vertices), shoelace formula.
double Area(const Polygon& p);

// The exact integral of f over the polygon: c * A + gx * Mx + gy * My with
// the first moments Mx = sum (x_i + x_{i+1}) cross_i / 6 (Green's theorem),
// signed like Area.
double Integral(const Polygon& p, const Linear& f);

// The part of `p` where Dot(n, q) <= d (Sutherland-Hodgman against one line).
Polygon ClipHalfPlane(const Polygon& p, V2 n, double d);

// p ∩ clip, both convex and counter-clockwise.
Polygon ClipConvex(const Polygon& p, const Polygon& clip);

// p ∩ [x0, x1] x [y0, y1].
Polygon ClipRect(const Polygon& p, double x0, double y0, double x1, double y1);

// a \ b as disjoint convex pieces: for the edges h_1..h_k of b, piece j is
// a ∩ inside(h_1) ∩ ... ∩ inside(h_{j-1}) ∩ outside(h_j). Pieces of area below
// `min_area` are dropped (slivers left by rounding).
std::vector<Polygon> SubtractConvex(const Polygon& a, const Polygon& b, double min_area = 1e-13);

// Point in a convex counter-clockwise polygon, boundary included.
bool Contains(const Polygon& p, V2 q);

// The parameters [t0, t1] ⊂ [0, 1] for which a + t (b - a) lies in the convex
// polygon (Cyrus-Beck); false when that part is empty or a single point.
bool ClipSegment(const Polygon& p, V2 a, V2 b, double* t0, double* t1);

// The exact integral of f along the segment a -> b (arc length), by the
// midpoint rule, which is exact for a linear f.
inline double SegmentIntegral(V2 a, V2 b, const Linear& f) {
  const V2 d = b - a;
  return std::hypot(d.x, d.y) * f(0.5 * (a + b));
}

// Axis-aligned bounds of a polygon.
struct Box {
  double x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  bool Overlaps(const Box& o) const { return x0 <= o.x1 && o.x0 <= x1 && y0 <= o.y1 && o.y0 <= y1; }
};
Box Bounds(const Polygon& p);

// A convex polygon made counter-clockwise (reversed when its area is
// negative).
Polygon MakeCounterClockwise(Polygon p);

}  // namespace alignset::render

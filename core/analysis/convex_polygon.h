#pragma once

#include <vector>

#include "core/util/angles.h"

namespace alignset {

// A convex polygon as its vertices in counter-clockwise order (empty when
// clipped away). The integrands of the analysis toolkit are built from such
// pieces, each carrying a linear function, because every quantity the
// variance needs has a closed form on them: the integral and the integral of
// the square (here) and the Fourier coefficients (polygon_fourier.h).
using Polygon = std::vector<Vec2>;

Polygon UnitSquarePolygon();

// The part of `polygon` where n.x >= c (Sutherland-Hodgman against one
// half-plane). Convex in, convex out.
Polygon ClipHalfPlane(const Polygon& polygon, Vec2 n, double c);

// Signed area (positive for counter-clockwise vertices).
double SignedArea(const Polygon& polygon);

// Whether p lies in the convex polygon (boundary included, up to 1e-12).
bool ContainsPoint(const Polygon& polygon, Vec2 p);

// A linear function h(x) = a + g.x.
struct LinearFunction {
  double a = 1.0;
  Vec2 g = {0.0, 0.0};
  double operator()(Vec2 p) const { return a + g.x * p.x + g.y * p.y; }
};

// The integral of h over the polygon, and of h squared (both exact: a
// triangle fan and the edge-midpoint rule, exact for quadratics).
double IntegrateLinear(const Polygon& polygon, const LinearFunction& h);
double IntegrateLinearSquared(const Polygon& polygon, const LinearFunction& h);

// The regular k-gon inscribed in the circle (centre, radius), first vertex at
// angle `rotation_deg`, counter-clockwise.
Polygon RegularPolygon(Vec2 centre, double radius, int k, double rotation_deg);

}  // namespace alignset

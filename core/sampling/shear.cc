#include "core/sampling/shear.h"

#include <cmath>

#include "core/util/angles.h"

namespace alignset {

PointSet Shear(const PointSet& points, double theta_deg) {
  // UnitVector is exact on the axes, so 0° and 90° are exact identities.
  const Vec2 d = UnitVector(theta_deg);
  double px = 0.0, py = 0.0;
  if (std::abs(d.x) >= std::sqrt(0.5)) {
    px = d.y / d.x;  // tan
  } else {
    py = d.x / d.y;  // cot
  }
  PointSet out(points.size());
  for (size_t i = 0; i < points.size(); ++i) {
    const Point2& s = points[i];
    out[i] = {Wrap01(s.x - px * s.y), Wrap01(s.y - py * s.x)};
  }
  return out;
}

}  // namespace alignset

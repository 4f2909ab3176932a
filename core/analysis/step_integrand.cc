#include "core/analysis/step_integrand.h"

#include <vector>

namespace alignset {
namespace {

// Area of the unit square cut to {(p - c).n >= 0}: Sutherland-Hodgman against
// one half-plane, then the shoelace formula.
double ClippedSquareArea(Vec2 n, double cx, double cy) {
  const std::vector<Vec2> square = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  auto side = [&](const Vec2& p) { return (p.x - cx) * n.x + (p.y - cy) * n.y; };
  std::vector<Vec2> poly;
  for (size_t i = 0; i < square.size(); ++i) {
    const Vec2& a = square[i];
    const Vec2& b = square[(i + 1) % square.size()];
    const double sa = side(a), sb = side(b);
    if (sa >= 0) poly.push_back(a);
    if ((sa >= 0) != (sb >= 0)) {
      const double t = sa / (sa - sb);
      poly.push_back({a.x + t * (b.x - a.x), a.y + t * (b.y - a.y)});
    }
  }
  double area = 0.0;
  for (size_t i = 0; i < poly.size(); ++i) {
    const Vec2& a = poly[i];
    const Vec2& b = poly[(i + 1) % poly.size()];
    area += a.x * b.y - a.y * b.x;
  }
  return 0.5 * std::abs(area);
}

}  // namespace

StepIntegrand::StepIntegrand(double normal_deg, double offset)
    : normal_deg_(normal_deg), n_(UnitVector(normal_deg)) {
  // UnitVector works on lines; keep the ray's orientation for angles >= 180.
  const double rad = DegToRad(normal_deg);
  if (std::abs(std::cos(rad) - n_.x) > 1e-9 || std::abs(std::sin(rad) - n_.y) > 1e-9) {
    n_ = {-n_.x, -n_.y};
  }
  cx_ = 0.5 + offset * n_.x;
  cy_ = 0.5 + offset * n_.y;
  integral_ = ClippedSquareArea(n_, cx_, cy_);
}

}  // namespace alignset

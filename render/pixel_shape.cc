#include "render/pixel_shape.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "render/direction.h"
#include "core/util/directions.h"

namespace alignset::render {

PixelShape ClassifyShape(const PixelIntegrand& f) {
  if (f.Classify() != PixelClass::kEdge) return PixelShape::kNone;
  std::vector<EdgePiece> pieces = f.Discontinuities();
  double total = 0.0;
  for (const EdgePiece& p : pieces) total += p.length * p.jump;
  std::erase_if(pieces, [&](const EdgePiece& p) { return p.length * p.jump < kNegligibleShare * total; });
  if (pieces.empty()) return PixelShape::kNone;
  std::sort(pieces.begin(), pieces.end(),
            [](const EdgePiece& a, const EdgePiece& b) { return a.length * a.jump > b.length * b.jump; });
  const double theta1 = pieces.front().normal_deg;
  double spread = 0.0;
  for (const EdgePiece& p : pieces) spread = std::max(spread, AxialDistanceDeg(p.normal_deg, theta1));
  if (spread > kCurvedSpreadDeg) return PixelShape::kCorner;
  if (spread > kSameDirectionDeg) return PixelShape::kCurved;
  // One direction: one line, or several parallel ones (their offsets along
  // the normal differ by more than a rounding error).
  const double r = theta1 * M_PI / 180.0;
  const V2 n{std::cos(r), std::sin(r)};
  double lo = Dot(n, pieces.front().a), hi = lo;
  for (const EdgePiece& p : pieces) {
    for (V2 q : {p.a, p.b}) lo = std::min(lo, Dot(n, q)), hi = std::max(hi, Dot(n, q));
  }
  return hi - lo > 1e-3 ? PixelShape::kParallel : PixelShape::kStraight;
}

std::string ShapeName(PixelShape s) {
  switch (s) {
    case PixelShape::kNone: return "none";
    case PixelShape::kStraight: return "straight";
    case PixelShape::kParallel: return "parallel";
    case PixelShape::kCurved: return "curved";
    case PixelShape::kCorner: return "corner";
  }
  return "?";
}

}  // namespace alignset::render

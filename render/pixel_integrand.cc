#include "render/pixel_integrand.h"

#include <algorithm>
#include <cmath>

#include "core/util/angles.h"

namespace alignset::render {

PixelIntegrand::PixelIntegrand(Linear background, std::vector<Fragment> fragments)
    : background_(background), fragments_(std::move(fragments)) {
  // A linear function's mean over the unit square is its value at the centre.
  exact_ = background_({0.5, 0.5});
  for (Fragment& f : fragments_) {
    f.box = Bounds(f.polygon);
    exact_ += Integral(f.polygon, f.shade) - Integral(f.polygon, background_);
  }
}

double PixelIntegrand::EvalWrapped(V2 u) const {
  return Eval({u.x - std::floor(u.x), u.y - std::floor(u.y)});
}

int PixelIntegrand::Owner(V2 u) const {
  for (size_t i = 0; i < fragments_.size(); ++i) {
    const Fragment& f = fragments_[i];
    if (u.x >= f.box.x0 && u.x <= f.box.x1 && u.y >= f.box.y0 && u.y <= f.box.y1 &&
        Contains(f.polygon, u)) {
      return static_cast<int>(i);
    }
  }
  return -1;
}

double PixelIntegrand::LineIntegral(V2 a, V2 b) const {
  double total = SegmentIntegral(a, b, background_);
  for (const Fragment& f : fragments_) {
    double t0, t1;
    if (!ClipSegment(f.polygon, a, b, &t0, &t1)) continue;
    const V2 pa = a + t0 * (b - a), pb = a + t1 * (b - a);
    total += SegmentIntegral(pa, pb, f.shade) - SegmentIntegral(pa, pb, background_);
  }
  return total;
}

namespace {
bool OnUnitSquareBoundary(V2 a, V2 b) {
  constexpr double kEps = 1e-12;
  auto same_line = [&](double pa, double pb, double c) {
    return std::abs(pa - c) < kEps && std::abs(pb - c) < kEps;
  };
  return same_line(a.x, b.x, 0.0) || same_line(a.x, b.x, 1.0) || same_line(a.y, b.y, 0.0) ||
         same_line(a.y, b.y, 1.0);
}
}  // namespace

std::vector<EdgePiece> PixelIntegrand::Discontinuities() const {
  // Each fragment edge is probed at a few points just outside it. A probe
  // landing in the background or in a later fragment counts; one landing in
  // an earlier fragment is left to that fragment's own edge, so a shared
  // edge counts once even where fragments meet at T-junctions.
  constexpr int kProbes = 8;
  constexpr double kOutside = 1e-7;
  std::vector<EdgePiece> out;
  for (size_t i = 0; i < fragments_.size(); ++i) {
    const Fragment& f = fragments_[i];
    for (size_t k = 0, n = f.polygon.size(); k < n; ++k) {
      const V2 a = f.polygon[k], b = f.polygon[(k + 1) % n];
      if (OnUnitSquareBoundary(a, b)) continue;
      const V2 e = b - a;
      const double len = std::hypot(e.x, e.y);
      if (len < 1e-12) continue;
      const V2 n_out = (1.0 / len) * V2{e.y, -e.x};
      double jump_sum = 0.0;
      int counted = 0;
      for (int j = 0; j < kProbes; ++j) {
        const V2 q = a + ((j + 0.5) / kProbes) * e;
        const V2 outside = q + kOutside * n_out;
        if (outside.x < 0.0 || outside.x > 1.0 || outside.y < 0.0 || outside.y > 1.0) continue;
        const int owner = Owner(outside);
        if (owner == static_cast<int>(i) || (owner >= 0 && owner < static_cast<int>(i))) continue;
        const double other = owner < 0 ? background_(q) : fragments_[owner].shade(q);
        jump_sum += std::abs(f.shade(q) - other);
        ++counted;
      }
      if (counted == 0) continue;
      const double jump = jump_sum / kProbes;  // uncounted probes add nothing
      if (jump < 1e-9) continue;
      EdgePiece piece;
      piece.a = a;
      piece.b = b;
      piece.length = len;
      piece.jump = jump;
      piece.normal_deg = ReduceDirection(std::atan2(e.y, e.x) * 180.0 / kPi + 90.0);
      out.push_back(piece);
    }
  }
  return out;
}

PixelClass PixelIntegrand::Classify() const {
  double weight = 0.0;
  for (const EdgePiece& e : Discontinuities()) weight += e.length * e.jump;
  if (weight >= kEdgeWeight) return PixelClass::kEdge;
  bool varies = false;
  auto has_gradient = [](const Linear& l) { return l.gx != 0.0 || l.gy != 0.0; };
  double covered = 0.0;
  for (const Fragment& f : fragments_) {
    covered += Area(f.polygon);
    if (has_gradient(f.shade)) varies = true;
  }
  if (covered < 1.0 - 1e-9 && has_gradient(background_)) varies = true;
  if (weight > 0.0) return PixelClass::kConstant;  // negligible edges: left out of both classes
  return varies ? PixelClass::kSmooth : PixelClass::kConstant;
}

std::vector<Fragment> Flatten(const std::vector<ShadedPolygon>& front_to_back, double min_area) {
  std::vector<Fragment> out;
  std::vector<Box> boxes;
  boxes.reserve(front_to_back.size());
  for (const ShadedPolygon& s : front_to_back) boxes.push_back(Bounds(s.polygon));
  for (size_t i = 0; i < front_to_back.size(); ++i) {
    std::vector<Polygon> pieces = {front_to_back[i].polygon};
    for (size_t j = 0; j < i && !pieces.empty(); ++j) {
      if (!boxes[i].Overlaps(boxes[j])) continue;
      std::vector<Polygon> next;
      for (const Polygon& p : pieces) {
        if (!Bounds(p).Overlaps(boxes[j])) {
          next.push_back(p);
          continue;
        }
        for (Polygon& q : SubtractConvex(p, front_to_back[j].polygon, min_area)) {
          next.push_back(std::move(q));
        }
      }
      pieces = std::move(next);
    }
    for (Polygon& p : pieces) {
      if (Area(p) < min_area) continue;
      Fragment f;
      f.box = Bounds(p);
      f.polygon = std::move(p);
      f.shade = front_to_back[i].shade;
      out.push_back(std::move(f));
    }
  }
  return out;
}

}  // namespace alignset::render

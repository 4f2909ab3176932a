#include "core/optimize/sliced_wasserstein.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "core/util/angles.h"

namespace alignset {

double ProjectionInverseCdf(double u, double deg) {
  const Vec2 d = UnitVector(deg);
  const double c = std::max(std::abs(d.x), std::abs(d.y));
  const double s = std::min(std::abs(d.x), std::abs(d.y));
  if (std::abs(u) <= (c - s) / (2.0 * c)) return u * c;
  const double tail = std::sqrt(std::max(0.0, 2.0 * s * c * (0.5 - std::abs(u))));
  return u > 0.0 ? (c + s) / 2.0 - tail : tail - (c + s) / 2.0;
}

std::vector<double> WassersteinTargets(uint32_t n, double deg) {
  const Vec2 d = UnitVector(deg);
  const double centre = 0.5 * (d.x + d.y);
  std::vector<double> t(n);
  for (uint32_t i = 0; i < n; ++i) {
    const double u = (static_cast<double>(i) + 0.5) / static_cast<double>(n) - 0.5;
    t[i] = ProjectionInverseCdf(u, deg) + centre;
  }
  return t;
}

namespace {

// Sorts `order` by (proj, index). Starts with an insertion sort, which costs
// O(N + inversions) on the previous call's order, and switches to std::sort
// once it has moved more than a few N elements.
void SortByProjection(const std::vector<double>& proj, std::vector<uint32_t>* order) {
  auto less = [&](uint32_t a, uint32_t b) {
    return proj[a] != proj[b] ? proj[a] < proj[b] : a < b;
  };
  std::vector<uint32_t>& o = *order;
  const size_t budget = 8 * o.size() + 64;
  size_t moved = 0;
  for (size_t i = 1; i < o.size(); ++i) {
    const uint32_t v = o[i];
    size_t j = i;
    while (j > 0 && less(v, o[j - 1])) {
      o[j] = o[j - 1];
      --j;
    }
    o[j] = v;
    moved += i - j;
    if (moved > budget) {
      std::sort(o.begin(), o.end(), less);
      return;
    }
  }
}

}  // namespace

SlicedWasserstein::SlicedWasserstein(uint32_t n, std::vector<double> directions_deg)
    : n_(n), directions_(std::move(directions_deg)) {
  for (double deg : directions_) targets_.push_back(WassersteinTargets(n_, deg));
}

double SlicedWasserstein::Evaluate(const PointSet& points, std::vector<Point2>* gradient) const {
  const size_t n = points.size();
  if (gradient) gradient->assign(n, {0.0, 0.0});
  if (n == 0 || directions_.empty()) return 0.0;
  const double inv_dirs = 1.0 / static_cast<double>(directions_.size());
  const double inv_n = 1.0 / static_cast<double>(n);
  std::vector<double> proj(n);
  orders_.resize(directions_.size());
  double total = 0.0;
  for (size_t k = 0; k < directions_.size(); ++k) {
    const Vec2 d = UnitVector(directions_[k]);
    for (size_t j = 0; j < n; ++j) proj[j] = points[j].x * d.x + points[j].y * d.y;
    std::vector<uint32_t>& order = orders_[k];
    if (order.size() != n) {
      order.resize(n);
      std::iota(order.begin(), order.end(), 0u);
    }
    SortByProjection(proj, &order);
    const std::vector<double>& t = targets_[k];
    double sum = 0.0;
    for (size_t i = 0; i < n; ++i) {
      const double r = proj[order[i]] - t[i];
      sum += r * r;
      if (gradient) {
        const double g = 2.0 * r * inv_n * inv_dirs;
        (*gradient)[order[i]].x += g * d.x;
        (*gradient)[order[i]].y += g * d.y;
      }
    }
    total += sum * inv_n;
  }
  return total * inv_dirs;
}

}  // namespace alignset

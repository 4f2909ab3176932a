#include "core/optimize/axis_stratification.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace alignset {
namespace {

// Sorts `order` by (coordinate, index), starting with an insertion sort that
// costs O(N + inversions) on a nearly sorted order and falling back to
// std::sort once it has moved more than a few N elements.
template <typename Coordinate>
void WarmSort(const PointSet& p, Coordinate coord, std::vector<uint32_t>* order) {
  std::vector<uint32_t>& o = *order;
  if (o.size() != p.size()) {
    o.resize(p.size());
    std::iota(o.begin(), o.end(), 0u);
  }
  auto less = [&](uint32_t a, uint32_t b) {
    const double ca = coord(p[a]), cb = coord(p[b]);
    return ca != cb ? ca < cb : a < b;
  };
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

template <typename Coordinate>
void ClampRanks(PointSet* points, Coordinate coord, double margin, std::vector<uint32_t>* order) {
  WarmSort(*points, [&](const Point2& q) { return coord(const_cast<Point2&>(q)); }, order);
  const double n = static_cast<double>(points->size());
  for (size_t r = 0; r < order->size(); ++r) {
    double& c = coord((*points)[(*order)[r]]);
    // Bounds whose stratum, floor(c N), is r in floating point too.
    double lo = (static_cast<double>(r) + margin) / n;
    while (std::floor(lo * n) < static_cast<double>(r)) lo = std::nextafter(lo, 1.0);
    double hi = std::nextafter((static_cast<double>(r + 1) - margin) / n, 0.0);
    while (std::floor(hi * n) > static_cast<double>(r)) hi = std::nextafter(hi, 0.0);
    c = std::clamp(c, lo, hi);
  }
}

}  // namespace

void AxisStratification::Apply(PointSet* points, double margin) {
  ClampRanks(points, [](Point2& q) -> double& { return q.x; }, margin, &order_x_);
  ClampRanks(points, [](Point2& q) -> double& { return q.y; }, margin, &order_y_);
}

size_t EmptyAxisStrata(const PointSet& points) {
  const size_t n = points.size();
  std::vector<char> column(n, 0), row(n, 0);
  for (const Point2& p : points) {
    column[std::min(n - 1, static_cast<size_t>(p.x * static_cast<double>(n)))] = 1;
    row[std::min(n - 1, static_cast<size_t>(p.y * static_cast<double>(n)))] = 1;
  }
  return static_cast<size_t>(std::count(column.begin(), column.end(), 0) +
                             std::count(row.begin(), row.end(), 0));
}

}  // namespace alignset

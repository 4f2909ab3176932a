#include "core/optimize/axis_stratification.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace alignset {
namespace {

// Sorts `keyed` by (coordinate, index), starting with an insertion sort that
// costs O(N + inversions) on a nearly sorted order and falling back to
// std::sort once it has moved more than a few N elements. The keys sit next
// to each other (not behind the point indices), so the nearly sorted pass
// streams through memory even at N = 65536.
void WarmSort(std::vector<std::pair<double, uint32_t>>* keyed) {
  std::vector<std::pair<double, uint32_t>>& o = *keyed;
  const size_t budget = 8 * o.size() + 64;
  size_t moved = 0;
  for (size_t i = 1; i < o.size(); ++i) {
    const std::pair<double, uint32_t> v = o[i];
    size_t j = i;
    while (j > 0 && v < o[j - 1]) {
      o[j] = o[j - 1];
      --j;
    }
    o[j] = v;
    moved += i - j;
    if (moved > budget) {
      std::sort(o.begin(), o.end());
      return;
    }
  }
}

template <typename Coordinate>
void ClampRanks(PointSet* points, Coordinate coord, const std::vector<double>& lo,
                const std::vector<double>& hi, std::vector<uint32_t>* order,
                std::vector<std::pair<double, uint32_t>>* keyed) {
  PointSet& p = *points;
  const size_t n = p.size();
  if (order->size() != n) {
    order->resize(n);
    std::iota(order->begin(), order->end(), 0u);
  }
  keyed->resize(n);
  // Starting from the previous call's order (nearly sorted between steps).
  for (size_t r = 0; r < n; ++r) (*keyed)[r] = {coord(p[(*order)[r]]), (*order)[r]};
  WarmSort(keyed);
  for (size_t r = 0; r < n; ++r) {
    const uint32_t i = (*keyed)[r].second;
    (*order)[r] = i;
    coord(p[i]) = std::clamp((*keyed)[r].first, lo[r], hi[r]);
  }
}

}  // namespace

void AxisStratification::Apply(PointSet* points, double margin) {
  const size_t n = points->size();
  if (lo_.size() != n || margin != bounds_margin_) {
    // Bounds of stratum r whose floor(c N) is r in floating point too; the
    // same for every step, so computed once.
    lo_.resize(n);
    hi_.resize(n);
    const double dn = static_cast<double>(n);
    for (size_t r = 0; r < n; ++r) {
      const double dr = static_cast<double>(r);
      double lo = (dr + margin) / dn;
      while (std::floor(lo * dn) < dr) lo = std::nextafter(lo, 1.0);
      double hi = std::nextafter((dr + 1.0 - margin) / dn, 0.0);
      while (std::floor(hi * dn) > dr) hi = std::nextafter(hi, 0.0);
      lo_[r] = lo;
      hi_[r] = hi;
    }
    bounds_margin_ = margin;
  }
  ClampRanks(points, [](Point2& q) -> double& { return q.x; }, lo_, hi_, &order_x_, &keyed_);
  ClampRanks(points, [](Point2& q) -> double& { return q.y; }, lo_, hi_, &order_y_, &keyed_);
}

void AxisStratification::ReleaseScratch() {
  // Moved-from empties free their memory (assigning {} would keep it).
  keyed_ = std::vector<std::pair<double, uint32_t>>();
  lo_ = std::vector<double>();
  hi_ = std::vector<double>();
  bounds_margin_ = -1.0;
}

size_t AxisStratification::HeldBytes() const {
  return (order_x_.capacity() + order_y_.capacity()) * sizeof(uint32_t) +
         keyed_.capacity() * sizeof(keyed_[0]) + (lo_.capacity() + hi_.capacity()) * sizeof(double);
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

#include "core/sampling/poisson_disk.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/util/hash.h"
#include "core/sampling/sampler_util.h"

namespace alignset {
namespace {

// Buckets of side >= r on the torus, so that every point within r of a query
// lies in the 3 x 3 buckets around it.
class TorusGrid {
 public:
  TorusGrid(double r, size_t capacity) {
    side_ = std::max(1, static_cast<int>(std::floor(1.0 / r)));
    head_.assign(static_cast<size_t>(side_) * side_, -1);
    next_.reserve(capacity);
    points_.reserve(capacity);
  }
  // True when no point lies closer than r (r no larger than at construction).
  bool Free(const Point2& p, double r) const {
    const double r2 = r * r;
    if (side_ < 3) {
      for (const Point2& q : points_) {
        if (TorusDistanceSquared(p, q) < r2) return false;
      }
      return true;
    }
    const int cx = CellOf(p.x), cy = CellOf(p.y);
    for (int dy = -1; dy <= 1; ++dy) {
      for (int dx = -1; dx <= 1; ++dx) {
        const int gx = (cx + dx + side_) % side_, gy = (cy + dy + side_) % side_;
        for (int32_t i = head_[static_cast<size_t>(gy) * side_ + gx]; i >= 0; i = next_[i]) {
          if (TorusDistanceSquared(p, points_[i]) < r2) return false;
        }
      }
    }
    return true;
  }
  void Insert(const Point2& p) {
    const size_t c = static_cast<size_t>(CellOf(p.y)) * side_ + CellOf(p.x);
    next_.push_back(head_[c]);
    head_[c] = static_cast<int32_t>(points_.size());
    points_.push_back(p);
  }
  const PointSet& points() const { return points_; }
  PointSet& points() { return points_; }

 private:
  int CellOf(double v) const { return std::min(side_ - 1, static_cast<int>(v * side_)); }
  int side_;
  std::vector<int32_t> head_, next_;
  PointSet points_;
};

PointSet BridsonRun(double r, uint64_t seed, size_t cap) {
  constexpr int kTries = 30;
  Pcg32 rng(seed);
  TorusGrid grid(r, cap);
  std::vector<uint32_t> active;
  grid.Insert({rng.NextDouble(), rng.NextDouble()});
  active.push_back(0);
  while (!active.empty() && grid.points().size() < cap) {
    const uint32_t slot = rng.Uniform(static_cast<uint32_t>(active.size()));
    const Point2 centre = grid.points()[active[slot]];
    bool found = false;
    for (int k = 0; k < kTries && !found; ++k) {
      // Uniform in the annulus [r, 2r] by rejection from its bounding square
      // (no trigonometry, so runs agree across libm versions).
      double dx, dy, d2;
      do {
        dx = (2.0 * rng.NextDouble() - 1.0) * 2.0 * r;
        dy = (2.0 * rng.NextDouble() - 1.0) * 2.0 * r;
        d2 = dx * dx + dy * dy;
      } while (d2 < r * r || d2 > 4.0 * r * r);
      const Point2 p{Wrap01(centre.x + dx), Wrap01(centre.y + dy)};
      if (grid.Free(p, r)) {
        grid.Insert(p);
        active.push_back(static_cast<uint32_t>(grid.points().size() - 1));
        found = true;
      }
    }
    if (!found) {
      active[slot] = active.back();
      active.pop_back();
    }
  }
  return std::move(grid.points());
}

}  // namespace

double HexagonalSpacing(uint32_t n) { return std::sqrt(2.0 / (std::sqrt(3.0) * n)); }

StatusOr<PointSet> PoissonDiskDartThrowing(uint32_t n, uint64_t seed, double* radius) {
  if (Status s = CheckSampleCount("poisson-dart", n); !s.ok()) return s;
  constexpr int kMissesBeforeShrinking = 4096;
  double r = 0.75 * HexagonalSpacing(n);
  Pcg32 rng(HashCombine(seed, 0x64617274ULL));
  TorusGrid grid(r, n);
  int misses = 0;
  while (grid.points().size() < n) {
    const Point2 p{rng.NextDouble(), rng.NextDouble()};
    if (grid.Free(p, r)) {
      grid.Insert(p);
      misses = 0;
    } else if (++misses >= kMissesBeforeShrinking) {
      r *= 0.98;
      misses = 0;
    }
  }
  if (radius) *radius = r;
  return std::move(grid.points());
}

StatusOr<PointSet> PoissonDiskBridson(uint32_t n, uint64_t seed, double* radius) {
  if (Status s = CheckSampleCount("poisson-bridson", n); !s.ok()) return s;
  // Bridson fills the torus at about 0.78 r_max (measured); aim a little
  // denser so the first run usually overshoots N by a few percent.
  double r = 0.76 * HexagonalSpacing(n);
  const uint64_t run_seed = HashCombine(seed, 0x6272696473ULL);
  // Let a run overshoot by at most 10 %; if it fills the cap, the radius is
  // too small and the excess would be a hole-free but uneven set.
  const size_t cap = static_cast<size_t>(n) + n / 10 + 1;
  PointSet points;
  for (int run = 0;; ++run) {
    points = BridsonRun(r, HashCombine(run_seed, run), cap);
    if (points.size() >= n && (points.size() < cap || run >= 12)) break;
    // Count scales with r^-2; aim 2 % above N.
    const double ratio = static_cast<double>(points.size()) / (1.02 * n);
    r *= std::clamp(std::sqrt(ratio), 0.9, 1.1);
    if (points.size() < n) r *= 0.995;
  }
  // Drop the excess at random.
  Pcg32 rng(HashCombine(run_seed, 0xd20bULL));
  for (size_t i = points.size(); i > n; --i) {
    const uint32_t j = rng.Uniform(static_cast<uint32_t>(i));
    points[j] = points[i - 1];
    points.pop_back();
  }
  if (radius) *radius = r;
  return points;
}

}  // namespace alignset

#include "core/sampling/pmj02.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "core/util/hash.h"
#include "core/sampling/sampler_util.h"

namespace alignset {
namespace {

uint64_t Prefix(uint32_t v, int bits) { return bits == 0 ? 0 : v >> (32 - bits); }

// Which elementary intervals of one level (area 2^-level) hold a point: one
// bit per cell for every shape a (2^a columns by 2^(level-a) rows).
class Occupancy {
 public:
  void Reset(int level) {
    level_ = level;
    bits_.assign((((static_cast<size_t>(level) + 1) << level) + 63) / 64, 0);
  }
  bool Occupied(int a, uint64_t x_prefix, uint64_t y_prefix) const {
    const size_t i = Index(a, x_prefix, y_prefix);
    return (bits_[i / 64] >> (i % 64)) & 1u;
  }
  void Mark(uint32_t x, uint32_t y) {
    for (int a = 0; a <= level_; ++a) {
      const size_t i = Index(a, Prefix(x, a), Prefix(y, level_ - a));
      bits_[i / 64] |= uint64_t{1} << (i % 64);
    }
  }

 private:
  size_t Index(int a, uint64_t x_prefix, uint64_t y_prefix) const {
    return (static_cast<size_t>(a) << level_) + ((x_prefix << (level_ - a)) | y_prefix);
  }
  int level_ = 0;
  std::vector<uint64_t> bits_;
};

// Nearest-neighbour distances on the torus over a uniform grid of 2^g x 2^g
// buckets, rebuilt at every doubling so that buckets hold a few points.
class NearestGrid {
 public:
  void Reset(int log_side, const std::vector<uint32_t>& xs, const std::vector<uint32_t>& ys) {
    log_side_ = log_side;
    side_ = 1u << log_side;
    head_.assign(static_cast<size_t>(side_) * side_, -1);
    next_.assign(xs.size(), -1);
    xs_ = &xs;
    ys_ = &ys;
    for (size_t i = 0; i < xs.size(); ++i) Insert(static_cast<int32_t>(i));
  }
  void Insert(int32_t i) {
    if (static_cast<size_t>(i) >= next_.size()) next_.resize(i + 1, -1);
    const size_t c = Cell((*xs_)[i], (*ys_)[i]);
    next_[i] = head_[c];
    head_[c] = i;
  }
  double MinDistanceSquared(uint32_t x, uint32_t y) const {
    const Point2 p{FromFixed32(x), FromFixed32(y)};
    double best = 2.0;
    const int cx = static_cast<int>(Prefix(x, log_side_)), cy = static_cast<int>(Prefix(y, log_side_));
    const double cell = 1.0 / side_;
    const int max_ring = static_cast<int>(side_ / 2);
    for (int r = 0; r <= max_ring; ++r) {
      // Points beyond ring r are at least r cells away.
      if (r > 0 && best <= (r - 1) * cell * (r - 1) * cell) break;
      for (int dy = -r; dy <= r; ++dy) {
        for (int dx = -r; dx <= r; ++dx) {
          if (std::max(std::abs(dx), std::abs(dy)) != r) continue;
          const int gx = (cx + dx) & static_cast<int>(side_ - 1);
          const int gy = (cy + dy) & static_cast<int>(side_ - 1);
          // Rings that wrap onto themselves would visit buckets twice.
          if (2 * r + 1 > static_cast<int>(side_) && Visited(cx, cy, gx, gy, r)) continue;
          for (int32_t i = head_[static_cast<size_t>(gy) * side_ + gx]; i >= 0; i = next_[i]) {
            best = std::min(best, TorusDistanceSquared(p, {FromFixed32((*xs_)[i]), FromFixed32((*ys_)[i])}));
          }
        }
      }
    }
    return best;
  }

 private:
  size_t Cell(uint32_t x, uint32_t y) const {
    return static_cast<size_t>(Prefix(y, log_side_)) * side_ + Prefix(x, log_side_);
  }
  // True when bucket (gx, gy) lies on a ring below r (already visited): its
  // toroidal Chebyshev distance from (cx, cy) is below r.
  bool Visited(int cx, int cy, int gx, int gy, int r) const {
    const int s = static_cast<int>(side_);
    int dx = std::abs(gx - cx), dy = std::abs(gy - cy);
    dx = std::min(dx, s - dx);
    dy = std::min(dy, s - dy);
    return std::max(dx, dy) != r;
  }
  int log_side_ = 0;
  uint32_t side_ = 1;
  std::vector<int32_t> head_, next_;
  const std::vector<uint32_t>* xs_ = nullptr;
  const std::vector<uint32_t>* ys_ = nullptr;
};

}  // namespace

StatusOr<PointSet> Pmj02(uint32_t n, uint64_t seed, int candidates) {
  const std::string name = candidates > 1 ? "pmj02bn" : "pmj02";
  if (Status s = CheckSampleCount(name, n); !s.ok()) return s;
  if (candidates < 1 || candidates > 256) {
    return Status::InvalidArgument(name + ": candidates must be in [1, 256], got " +
                                   std::to_string(candidates));
  }
  Pcg32 rng(HashCombine(seed, 0x706d6a3032ULL));
  std::vector<uint32_t> xs, ys;
  xs.reserve(n);
  ys.reserve(n);
  xs.push_back(rng.NextU32());
  ys.push_back(rng.NextU32());

  Occupancy occupancy;
  NearestGrid grid;
  Status failure;
  uint32_t m = 1;
  int log_m = 0;

  // One new point in one of `options` sub-quadrants (t bits each) of the
  // level-`level` net; candidates alternate between the options, and the one
  // that wins is reported in `chosen`.
  using Quadrant = std::pair<uint64_t, uint64_t>;
  auto place = [&](const std::vector<Quadrant>& options, int t, int level, Quadrant* chosen) {
    uint32_t best_x = 0, best_y = 0;
    double best_d = -1.0;
    const uint32_t first_option = options.size() > 1 ? rng.NextU32() & 1u : 0u;
    for (int c = 0; c < candidates; ++c) {
      const Quadrant q = options[(first_option + c) % options.size()];
      const uint64_t qx = q.first, qy = q.second;
      uint64_t x = qx, y = qy;
      bool ok = true;
      const uint32_t x_bits = rng.NextU32(), y_bits = rng.NextU32();
      for (int a = t + 1; a <= level && ok; ++a) {  // x digit a: shape a
        const uint64_t y_prefix = qy >> (t - (level - a));
        x = (x << 1) | ((x_bits >> a) & 1u);
        if (occupancy.Occupied(a, x, y_prefix)) {
          x ^= 1;
          ok = !occupancy.Occupied(a, x, y_prefix);
        }
      }
      for (int b = t + 1; b <= level && ok; ++b) {  // y digit b: shape level - b
        const int a = level - b;
        const uint64_t x_prefix = qx >> (t - a);
        y = (y << 1) | ((y_bits >> b) & 1u);
        if (occupancy.Occupied(a, x_prefix, y)) {
          y ^= 1;
          ok = !occupancy.Occupied(a, x_prefix, y);
        }
      }
      for (int a = 0; a <= level && ok; ++a) {
        ok = !occupancy.Occupied(a, x >> (level - a), y >> a);
      }
      if (!ok) continue;
      // Below the net's resolution: uniform.
      const uint32_t fx = static_cast<uint32_t>(x << (32 - level)) | (rng.NextU32() >> level);
      const uint32_t fy = static_cast<uint32_t>(y << (32 - level)) | (rng.NextU32() >> level);
      const double d = candidates > 1 ? grid.MinDistanceSquared(fx, fy) : 0.0;
      if (d > best_d) {
        best_d = d;
        best_x = fx;
        best_y = fy;
        if (chosen) *chosen = q;
      }
    }
    if (best_d < 0.0) {
      failure = Status::Internal(name + ": no valid position at level " + std::to_string(level) +
                                 " (a bug: the construction has no dead ends)");
      return false;
    }
    xs.push_back(best_x);
    ys.push_back(best_y);
    occupancy.Mark(best_x, best_y);
    if (candidates > 1) grid.Insert(static_cast<int32_t>(xs.size() - 1));
    return true;
  };

  while (xs.size() < n) {
    const int level = log_m + 1;
    const int t = log_m / 2 + 1;  // sub-quadrant digits: strata of 4^k points have k
    occupancy.Reset(level);
    for (size_t i = 0; i < xs.size(); ++i) occupancy.Mark(xs[i], ys[i]);
    if (candidates > 1) grid.Reset(std::max(0, log_m / 2), xs, ys);

    if (log_m % 2 == 0) {
      for (uint32_t s = 0; s < m && xs.size() < n; ++s) {
        if (!place({{Prefix(xs[s], t) ^ 1u, Prefix(ys[s], t) ^ 1u}}, t, level, nullptr)) {
          return failure;
        }
      }
    } else {
      std::vector<Quadrant> second(m / 2);
      for (uint32_t s = 0; s < m / 2 && xs.size() < n; ++s) {
        const uint64_t qx = Prefix(xs[s], t), qy = Prefix(ys[s], t);
        // The two free sub-quadrants of the parent's stratum (the other two
        // hold the parent and its diagonal sibling): either may come first.
        Quadrant first;
        if (!place({{qx ^ 1u, qy}, {qx, qy ^ 1u}}, t, level, &first)) return failure;
        second[s] = {first.first ^ 1u, first.second ^ 1u};
      }
      for (uint32_t s = 0; s < m / 2 && xs.size() < n; ++s) {
        if (!place({second[s]}, t, level, nullptr)) return failure;
      }
    }
    m *= 2;
    ++log_m;
  }

  PointSet points(n);
  for (uint32_t i = 0; i < n; ++i) points[i] = {FromFixed32(xs[i]), FromFixed32(ys[i])};
  return points;
}

}  // namespace alignset

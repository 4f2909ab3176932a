#include "core/optimize/aligned_lattice.h"

#include <algorithm>
#include <atomic>
#include <iterator>
#include <tuple>
#include <thread>
#include <cmath>
#include <complex>
#include <numeric>
#include <string>
#include <utility>

#include "core/analysis/convex_polygon.h"
#include "core/analysis/integer_indicator_spectrum.h"
#include "core/analysis/lattice_variance.h"
#include "core/optimize/optimizer.h"
#include "core/spectral/direction_budget.h"
#include "core/util/angles.h"
#include "core/util/hash.h"

namespace alignset {
namespace {

// Offsets of the scored edges from the centre, along their normal: one
// through the centre and two that cut the square unevenly.
constexpr double kEdgeOffsets[] = {0.0, 0.21, -0.33};
constexpr double kCornerWeight = 0.5;
// The window is sampled at 2 kWindowSteps + 1 angles.
constexpr int kWindowSteps = 4;
constexpr uint32_t kFullSearchLimit = 65536;
// A family's coefficient tables may take this much memory (a two-direction
// family at N = 32768 takes 56 MB); above it the vertices' factors are
// computed on the spot.
constexpr double kMaxTableBytes = 64e6;

struct Family {
  std::vector<IntegerIndicatorSpectrum> edges;
};

// The edges scored: for each direction, 2 steps + 1 normals across the
// window, each through `offsets` of the kEdgeOffsets; their coefficients
// tabulated for the dual points within `radius`.
Family ScoredFamily(const std::vector<double>& directions_deg, double window_deg, int steps,
                    size_t offsets, int radius) {
  // Each edge's square has two vertices off the corners, one table each.
  const double bytes = static_cast<double>(directions_deg.size()) * (2 * steps + 1) * offsets * 2.0 *
                       (2.0 * radius + 1.0) * sizeof(std::complex<double>);
  const bool tabulate = bytes <= kMaxTableBytes;
  Family f;
  for (double d : directions_deg) {
    for (int k = -steps; k <= steps; ++k) {
      const double delta = window_deg * k / steps;
      const Vec2 n = UnitVector(d + delta);
      for (size_t o = 0; o < offsets; ++o) {
        const double offset = kEdgeOffsets[o];
        const double c = 0.5 * (n.x + n.y) + offset;
        Polygon p = ClipHalfPlane(UnitSquarePolygon(), n, c);
        if (SignedArea(p) > 1e-12) f.edges.emplace_back(p, radius, tabulate);
      }
    }
  }
  return f;
}

// The score of one generator: the mean log variance of the family's edges
// plus kCornerWeight times the log variance of the corner term, over the
// dual points within `radius`.
double Score(uint32_t n, uint32_t g, int radius, const Family& family) {
  const std::vector<Frequency> dual = Rank1DualHalfDisk(n, g, radius);
  std::vector<double> edge_sum(family.edges.size(), 0.0);
  double corner = 0.0;
  for (const Frequency& h : dual) {
    const double hx = h.a, hy = h.b;
    for (size_t k = 0; k < family.edges.size(); ++k) {
      edge_sum[k] += family.edges[k].Energy(h.a, h.b);
    }
    // (x - 1/2)(y - 1/2): coefficients i/(2 pi a) * i/(2 pi b) off the axes.
    if (h.a != 0 && h.b != 0) corner += 1.0 / (16.0 * std::pow(kPi, 4) * hx * hx * hy * hy);
  }
  // Each half-disk point stands for +-h: the factor 2 keeps these variances.
  // The floor, a tenth of what a good lattice reaches (about 0.3 / N^2), keeps
  // one member that a degenerate lattice integrates exactly (g = 1 and the
  // edge through the centre at 45 degrees: its dual misses that edge's
  // coefficients, while the set is a line) from outweighing all others.
  const double floor = 0.1 / (static_cast<double>(n) * n);
  double score = 0.0;
  for (double s : edge_sum) score += std::log(2.0 * s + floor);
  score /= static_cast<double>(std::max<size_t>(1, edge_sum.size()));
  return score + kCornerWeight * std::log(2.0 * corner + floor);
}

// A score rounded to 2^-30 (about 1e-9; scores are logs near -10...-40):
// generators a symmetry makes equally good (a direction and its mirror
// about 45 degrees swap g and its inverse) differ by rounding alone, in the
// last digits, and rounding must not be what picks one; rounded, they tie
// and the smaller g wins, as the header promises.
double Quantized(double score) { return std::ldexp(std::nearbyint(std::ldexp(score, 30)), -30); }

// Scores every (score, g) entry in place, on `threads` threads (0: all
// cores); each score depends on its g alone, so the result does not depend
// on the thread count.
void ScoreAll(uint32_t n, int radius, const Family& family, int threads,
              std::vector<std::pair<double, uint32_t>>* ranked) {
  const size_t count = ranked->size();
  size_t workers = threads > 0 ? static_cast<size_t>(threads)
                               : std::max(1u, std::thread::hardware_concurrency());
  workers = std::min(workers, std::max<size_t>(1, count / 16));
  std::atomic<size_t> next{0};
  auto work = [&] {
    for (size_t i = next++; i < count; i = next++) {
      (*ranked)[i].first = Quantized(Score(n, (*ranked)[i].second, radius, family));
    }
  };
  std::vector<std::thread> pool;
  for (size_t t = 1; t < workers; ++t) pool.emplace_back(work);
  work();
  for (std::thread& t : pool) t.join();
}

Status Validate(uint32_t n, const std::vector<double>& directions, const AlignedLatticeOptions& o) {
  if (n < kMinPoints || n > kMaxPoints) {
    return Status::InvalidArgument("aligned lattice: N must be in [" + std::to_string(kMinPoints) +
                                   ", " + std::to_string(kMaxPoints) + "], got " +
                                   std::to_string(n));
  }
  if (directions.empty() || directions.size() > static_cast<size_t>(kMaxArbitraryDirections)) {
    return Status::InvalidArgument("aligned lattice: 1 to " +
                                   std::to_string(kMaxArbitraryDirections) +
                                   " directions, got " + std::to_string(directions.size()));
  }
  for (double d : directions) {
    if (!std::isfinite(d)) return Status::InvalidArgument("aligned lattice: a direction is not finite");
  }
  if (!(o.window_deg >= 0.0 && o.window_deg <= 10.0)) {
    return Status::InvalidArgument("aligned lattice: window_deg must be in [0, 10]");
  }
  if (o.threads < 0) return Status::InvalidArgument("aligned lattice: threads must be >= 0");
  if (o.finalists < 1) return Status::InvalidArgument("aligned lattice: finalists must be >= 1");
  return Status::Ok();
}

}  // namespace

namespace {

// The two stages' radii: all dual points within N / 2 in the final one,
// within 8 sqrt(N) (at least 32) in the first.
int FullRadius(uint32_t n) { return static_cast<int>(n / 2); }
int FirstRadius(uint32_t n) {
  return std::min(FullRadius(n), std::max(32, static_cast<int>(std::lround(8.0 * std::sqrt(n)))));
}

// Modular inverse of g (coprime to n), by the extended Euclidean algorithm.
uint32_t InverseMod(uint32_t g, uint32_t n) {
  int64_t r0 = n, r1 = g % n, t0 = 0, t1 = 1;
  while (r1 != 0) {
    const int64_t q = r0 / r1;
    std::tie(r0, r1) = std::make_pair(r1, r0 - q * r1);
    std::tie(t0, t1) = std::make_pair(t1, t0 - q * t1);
  }
  return static_cast<uint32_t>(((t0 % n) + n) % n);
}

}  // namespace

StatusOr<double> AlignedLatticeScore(uint32_t n, uint32_t g, const std::vector<double>& directions_deg,
                                     const AlignedLatticeOptions& options) {
  if (Status s = Validate(n, directions_deg, options); !s.ok()) return s;
  if (g == 0 || g >= n || std::gcd(g, n) != 1) {
    return Status::InvalidArgument("aligned lattice: g = " + std::to_string(g) + " is not a generator coprime to N = " +
                                   std::to_string(n));
  }
  const int r_full = FullRadius(n), r_first = FirstRadius(n);
  if (r_full > r_first) {
    const Family family = ScoredFamily(directions_deg, options.window_deg, kWindowSteps,
                                       std::size(kEdgeOffsets), r_full);
    return Quantized(Score(n, g, r_full, family));
  }
  return Quantized(Score(n, g, r_first, ScoredFamily(directions_deg, options.window_deg, 1, 2, r_first)));
}

uint32_t MapLatticeGenerator(uint32_t n, uint32_t g, const AlignOps& ops) {
  uint32_t m = ops.swap ? InverseMod(g, n) : g % n;
  if (ops.invert) m = (n - m) % n;
  if (ops.invert_y) m = (n - m) % n;
  return m;
}

StatusOr<AlignedLatticeChoice> ChooseAlignedLatticeGenerator(
    uint32_t n, const std::vector<double>& directions_deg, const AlignedLatticeOptions& options) {
  if (Status s = Validate(n, directions_deg, options); !s.ok()) return s;
  // The first stage sees a coarse family (the window's ends and middle, two
  // offsets): it only has to keep the finalists, and it scores every g.
  const int r_full = FullRadius(n);
  const int r_first = FirstRadius(n);
  const Family coarse = ScoredFamily(directions_deg, options.window_deg, 1, 2, r_first);
  const uint32_t stride = n > kFullSearchLimit ? (n + kFullSearchLimit - 1) / kFullSearchLimit : 1;

  std::vector<std::pair<double, uint32_t>> ranked;
  for (uint32_t g = 1; g < n; g += stride) {
    if (std::gcd(g, n) == 1) ranked.push_back({0.0, g});
  }
  ScoreAll(n, r_first, coarse, options.threads, &ranked);
  AlignedLatticeChoice choice;
  choice.candidates = static_cast<uint32_t>(ranked.size());
  const size_t keep = std::min(ranked.size(), static_cast<size_t>(options.finalists));
  std::partial_sort(ranked.begin(), ranked.begin() + keep, ranked.end());
  ranked.resize(keep);
  if (r_full > r_first) {
    const Family family = ScoredFamily(directions_deg, options.window_deg, kWindowSteps,
                                       std::size(kEdgeOffsets), r_full);
    ScoreAll(n, r_full, family, options.threads, &ranked);
    std::sort(ranked.begin(), ranked.end());
  }
  choice.generator = ranked.front().second;
  choice.score = ranked.front().first;
  return choice;
}

PointSet Rank1LatticePoints(uint32_t n, uint32_t g, uint64_t seed) {
  Pcg32 rng(HashCombine(seed, 0x616c6c6174ULL));
  const uint64_t sx = rng.Uniform(n), sy = rng.Uniform(n);
  PointSet points(n);
  const double inv = 1.0 / n;
  for (uint64_t i = 0; i < n; ++i) {
    points[i] = {(static_cast<double>((i + sx) % n) + 0.5) * inv,
                 (static_cast<double>((i * g + sy) % n) + 0.5) * inv};
  }
  return points;
}

StatusOr<PointSet> AlignedLattice(uint32_t n, const std::vector<double>& directions_deg,
                                  uint64_t seed, const AlignedLatticeOptions& options) {
  auto choice = ChooseAlignedLatticeGenerator(n, directions_deg, options);
  if (!choice.ok()) return choice.status();
  return Rank1LatticePoints(n, choice->generator, seed);
}

}  // namespace alignset

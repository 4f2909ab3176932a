#include "core/optimize/aligned_lattice.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <tuple>
#include <utility>
#include <vector>

#include "core/sampling/rank1_lattice.h"
#include "core/util/hash.h"

// The points of a chosen lattice and its symmetries: apart from the
// generator search (aligned_lattice.cc), so that a renderer's sampler links
// them without the search's spectra and engines.
namespace alignset {

uint32_t MapLatticeGenerator(uint32_t n, uint32_t g, bool swap, bool invert_x, bool invert_y) {
  uint32_t m = swap ? Rank1InverseMod(g, n) : g % n;
  if (invert_x) m = (n - m) % n;
  if (invert_y) m = (n - m) % n;
  return m;
}

namespace {

// The shift of the plain lattice's realization `seed`: whole cells (plus
// the half cell Rank1LatticePoints adds); the folded lattice's is continuous
// (TentLatticeShift).
struct CellShift {
  uint64_t x, y;
};
CellShift PlainShift(uint32_t n, uint64_t seed) {
  Pcg32 rng(HashCombine(seed, 0x616c6c6174ULL));
  const uint64_t sx = rng.Uniform(n);
  return {sx, rng.Uniform(n)};
}

}  // namespace

Point2 TentLatticeShift(uint64_t seed) {
  Pcg32 rng(HashCombine(seed, 0x74656e74ULL));
  const double sx = rng.NextDouble();
  return {sx, rng.NextDouble()};
}

PointSet Rank1LatticePoints(uint32_t n, uint32_t g, uint64_t seed) {
  PointSet points(n);
  Rank1LatticePointsInto(n, g, seed, points);
  return points;
}

void Rank1LatticePointsInto(uint32_t n, uint32_t g, uint64_t seed, std::span<Point2> out) {
  const CellShift shift = PlainShift(n, seed);
  const uint64_t sx = shift.x, sy = shift.y;
  const double inv = 1.0 / n;
  const uint64_t count = std::min<uint64_t>(n, out.size());
  for (uint64_t i = 0; i < count; ++i) {
    out[i] = {(static_cast<double>((i + sx) % n) + 0.5) * inv, (static_cast<double>((i * g + sy) % n) + 0.5) * inv};
  }
}

PointSet TentLatticePoints(uint32_t n, uint32_t g, uint64_t seed) {
  const Point2 shift = TentLatticeShift(seed);
  const double sx = shift.x, sy = shift.y;
  PointSet points(n);
  const double inv = 1.0 / n;
  for (uint64_t i = 0; i < n; ++i) {
    double x = static_cast<double>(i) * inv + sx, y = static_cast<double>((i * g) % n) * inv + sy;
    x -= std::floor(x), y -= std::floor(y);
    // The fold of u in [0, 1) lies in [0, 1]; 1 itself (u = 1/2 exactly) is
    // kept inside the half-open square the sets live in.
    points[i] = {std::min(TentFold(x), std::nextafter(1.0, 0.0)), std::min(TentFold(y), std::nextafter(1.0, 0.0))};
  }
  return points;
}

PointSet LatticePoints(uint32_t n, uint32_t g, uint64_t seed, bool folded) {
  return folded ? TentLatticePoints(n, g, seed) : Rank1LatticePoints(n, g, seed);
}

std::optional<uint32_t> LatticeGeneratorOf(const PointSet& points, uint64_t seed, bool folded) {
  if (points.size() < 2 || points.size() > std::numeric_limits<uint32_t>::max()) return std::nullopt;
  const uint32_t n = static_cast<uint32_t>(points.size());
  // Point 1 is the lattice's (1, g) / N moved by the realization's shift:
  // its y gives g, up to the fold's two preimages and rounding.
  std::vector<int64_t> guesses;
  if (folded) {
    const double sy = TentLatticeShift(seed).y;
    for (double u : {0.5 * points[1].y, 1.0 - 0.5 * points[1].y}) {
      guesses.push_back(static_cast<int64_t>(std::llround((u - sy) * n)));
    }
  } else {
    const CellShift shift = PlainShift(n, seed);
    guesses.push_back(static_cast<int64_t>(std::llround(points[1].y * n - 0.5)) -
                      static_cast<int64_t>(shift.y));
  }
  const int64_t nn = n;
  for (int64_t guess : guesses) {
    for (int64_t d : {0, -1, 1}) {
      const uint32_t g = static_cast<uint32_t>((((guess + d) % nn) + nn) % nn);
      if (std::gcd(g, n) != 1) continue;
      if (LatticePoints(n, g, seed, folded) == points) return g;
    }
  }
  return std::nullopt;
}

}  // namespace alignset

#include <algorithm>
#include <cmath>

#include "core/optimize/lattice_sequence.h"
#include "core/util/hash.h"

// The sequence's points: apart from its search (lattice_sequence.cc), so a
// renderer's sampler links them without the searches.
namespace alignset {

Point2 LatticeSequenceShift(uint64_t seed) {
  Pcg32 rng(HashCombine(seed, 0x6c73657175656e63ULL));
  const double sx = rng.NextDouble();
  return {sx, rng.NextDouble()};
}

void LatticeSequencePointsInto(uint32_t g, uint64_t seed, std::span<Point2> out) {
  const Point2 s = LatticeSequenceShift(seed);
  const size_t count = std::min<size_t>(out.size(), kLatticeSequenceMaxPoints);
  constexpr double kInv = 1.0 / kLatticeSequenceMaxPoints;
  constexpr uint32_t kMask = kLatticeSequenceMaxPoints - 1;
  for (size_t i = 0; i < count; ++i) {
    // phi(i) 2^16: i's 16 bits reversed.
    const uint32_t r = ReverseBits32(static_cast<uint32_t>(i)) >> (32 - kLatticeSequenceLog2);
    double x = r * kInv + s.x, y = ((r * g) & kMask) * kInv + s.y;
    x -= std::floor(x), y -= std::floor(y);
    out[i] = {x, y};
  }
}

PointSet LatticeSequencePoints(uint32_t n, uint32_t g, uint64_t seed) {
  PointSet points(std::min(n, kLatticeSequenceMaxPoints));
  LatticeSequencePointsInto(g, seed, points);
  return points;
}

}  // namespace alignset

#pragma once

#include <cstdint>
#include <span>

#include "core/util/point_set.h"

namespace alignset {

// The first two dimensions of the Sobol sequence, Owen-scrambled with the
// hash-based nested uniform scramble of Burley 2020 ("Practical Hash-based
// Owen Scrambling"): the index is shuffled by one scramble and each dimension
// by its own, all derived from `seed`. For N = 2^m the result is a (0,m,2)-net:
// every elementary interval of area 1/N holds exactly one point. Other N take
// the first N points of the shuffled sequence (still well stratified).
PointSet OwenScrambledSobol(uint32_t n, uint64_t seed);
// Points first, first + 1, ... of the same sequence into `out`, bit for bit
// OwenScrambledSobol's, without allocating (a renderer's per-pixel loop).
void OwenScrambledSobolInto(uint64_t seed, uint32_t first, std::span<Point2> out);

// The unscrambled i-th point's 32-bit digits, for tests and other samplers.
uint32_t SobolDim0(uint32_t index);
uint32_t SobolDim1(uint32_t index);

}  // namespace alignset

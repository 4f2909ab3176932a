#include "core/sampling/owen_sobol.h"

#include <array>

#include "core/util/hash.h"

namespace alignset {
namespace {

// Generator of Sobol's second dimension (primitive polynomial x + 1): column k
// is the previous column XOR itself shifted right, i.e. Pascal's triangle mod 2.
constexpr std::array<uint32_t, 32> MakeDim1Columns() {
  std::array<uint32_t, 32> c{};
  c[0] = 0x80000000u;
  for (int k = 1; k < 32; ++k) c[k] = c[k - 1] ^ (c[k - 1] >> 1);
  return c;
}
constexpr std::array<uint32_t, 32> kDim1Columns = MakeDim1Columns();

double ToUnit(uint32_t v) {
  // 32 bits of the digit expansion; the result is < 1 exactly.
  return static_cast<double>(v) * 0x1.0p-32;
}

}  // namespace

uint32_t SobolDim0(uint32_t index) { return ReverseBits32(index); }

uint32_t SobolDim1(uint32_t index) {
  uint32_t v = 0;
  for (int k = 0; index != 0; ++k, index >>= 1) {
    if (index & 1u) v ^= kDim1Columns[k];
  }
  return v;
}

PointSet OwenScrambledSobol(uint32_t n, uint64_t seed) {
  PointSet points(n);
  OwenScrambledSobolInto(seed, 0, points);
  return points;
}

void OwenScrambledSobolInto(uint64_t seed, uint32_t first, std::span<Point2> out) {
  const uint32_t index_seed = static_cast<uint32_t>(HashCombine(seed, 0));
  const uint32_t seed_x = static_cast<uint32_t>(HashCombine(seed, 1));
  const uint32_t seed_y = static_cast<uint32_t>(HashCombine(seed, 2));
  for (size_t k = 0; k < out.size(); ++k) {
    // Shuffling the index with a nested uniform scramble keeps every
    // power-of-two prefix a net (Burley 2020, section 4).
    const uint32_t j = NestedUniformScramble(first + static_cast<uint32_t>(k), index_seed);
    out[k].x = ToUnit(NestedUniformScramble(SobolDim0(j), seed_x));
    out[k].y = ToUnit(NestedUniformScramble(SobolDim1(j), seed_y));
  }
}

}  // namespace alignset

#pragma once

// The Sobol sequence in many dimensions, for samplers that pad a renderer's
// later dimensions with one jointly indexed sequence (a path's later bounces
// stratified together, as pbrt's "sobol" stratifies them), where
// owen_sobol.h has the first two dimensions only.
//
// The direction numbers are Joe and Kuo's (new-joe-kuo-6.21201, the
// construction with better two-dimensional projections), read from
// Boost.Random's table of them (Debian's libboost-dev) rather than copied in.

#include <cstdint>
#include <vector>

namespace alignset {

// The dimensions Boost.Random's table holds.
inline constexpr uint32_t kSobolMaxDimensions = 3667;
inline constexpr uint32_t kSobolDigits = 32;

// Dimensions [0, dimensions) (dimensions <= kSobolMaxDimensions): entry
// d * kSobolDigits + j is the 32 digits that bit j of the index flips in
// dimension d. Dimension 0 is the van der Corput sequence, dimension 1 the
// x + 1 polynomial's (owen_sobol.h's two, bit for bit).
std::vector<uint32_t> SobolDirectionNumbers(uint32_t dimensions);

// The unscrambled point `index`'s digits in the dimension whose kSobolDigits
// direction numbers start at `directions`.
inline uint32_t SobolDigits(const uint32_t* directions, uint32_t index) {
  uint32_t x = 0;
  for (; index != 0; index >>= 1, ++directions) {
    if (index & 1u) x ^= *directions;
  }
  return x;
}

}  // namespace alignset

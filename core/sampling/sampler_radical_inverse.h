#pragma once

#include <cstdint>
#include <vector>

#include "core/util/point_set.h"
#include "core/util/status.h"

namespace alignset {

// The classic radical-inverse samplers: Halton (bases 2 and 3) and
// Hammersley (i / N and base 2), plain or scrambled by random digit
// permutations (one uniform permutation of the base's digits per digit
// position and dimension, drawn from the seed, applied to every digit
// including the trailing zeros, as in Faure & Tezuka's and pbrt's
// "permutation" scramble). Plain versions ignore the seed. Any N.
StatusOr<PointSet> Halton(uint32_t n, uint64_t seed, bool scrambled);
StatusOr<PointSet> Hammersley(uint32_t n, uint64_t seed, bool scrambled);
// The unscrambled Sobol (0,2)-sequence, first N points.
StatusOr<PointSet> Sobol(uint32_t n);

// Phi_b(i): the digits of i in base b mirrored about the radix point.
// Exact: the mirrored digits are accumulated as an integer below 2^53.
double RadicalInverse(uint32_t base, uint64_t index);

// A fixed set of digit permutations for one base (the scramble of one
// dimension).
class DigitPermutations {
 public:
  DigitPermutations(uint32_t base, uint64_t seed);
  // Phi_b(i) with digit k replaced by perm_k(digit k).
  double Apply(uint64_t index) const;
  uint32_t base() const { return base_; }

 private:
  uint32_t base_;
  int digits_;  // base^digits_ <= 2^53
  std::vector<std::vector<uint8_t>> perm_;
};

}  // namespace alignset

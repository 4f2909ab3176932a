#include "core/sampling/sampler_radical_inverse.h"

#include <algorithm>
#include <cmath>

#include "core/util/hash.h"
#include "core/sampling/owen_sobol.h"
#include "core/sampling/sampler_util.h"

namespace alignset {
namespace {

// The number of base-b digits whose mirrored integer stays below 2^53, so
// that value = integer / b^digits is one correctly rounded division.
int DigitsFor(uint32_t base) {
  int d = 0;
  uint64_t p = 1;
  while (p <= (uint64_t{1} << 53) / base) {
    p *= base;
    ++d;
  }
  return d;
}

double MirroredToUnit(uint64_t mirrored, uint32_t base, int digits) {
  double scale = 1.0;
  for (int k = 0; k < digits; ++k) scale *= base;  // exact: base^digits <= 2^53
  // mirrored < base^digits, and the quotient rounds below 1.0 for any base
  // here; the clamp keeps that a guarantee rather than an observation.
  return std::min(static_cast<double>(mirrored) / scale, std::nextafter(1.0, 0.0));
}

}  // namespace

double RadicalInverse(uint32_t base, uint64_t index) {
  const int digits = DigitsFor(base);
  uint64_t mirrored = 0;
  for (int k = 0; k < digits; ++k) {
    mirrored = mirrored * base + index % base;
    index /= base;
  }
  return MirroredToUnit(mirrored, base, digits);
}

DigitPermutations::DigitPermutations(uint32_t base, uint64_t seed)
    : base_(base), digits_(DigitsFor(base)) {
  Pcg32 rng(HashCombine(seed, base));
  perm_.resize(digits_);
  for (auto& p : perm_) {
    const std::vector<uint32_t> q = RandomPermutation(base, rng);
    p.assign(q.begin(), q.end());
  }
}

double DigitPermutations::Apply(uint64_t index) const {
  uint64_t mirrored = 0;
  for (int k = 0; k < digits_; ++k) {
    mirrored = mirrored * base_ + perm_[k][index % base_];
    index /= base_;
  }
  return MirroredToUnit(mirrored, base_, digits_);
}

StatusOr<PointSet> Halton(uint32_t n, uint64_t seed, bool scrambled) {
  if (Status s = CheckSampleCount(scrambled ? "halton-scrambled" : "halton", n); !s.ok()) return s;
  const DigitPermutations px(2, HashCombine(seed, 11)), py(3, HashCombine(seed, 12));
  PointSet points(n);
  for (uint32_t i = 0; i < n; ++i) {
    points[i] = scrambled ? Point2{px.Apply(i), py.Apply(i)}
                          : Point2{RadicalInverse(2, i), RadicalInverse(3, i)};
  }
  return points;
}

StatusOr<PointSet> Hammersley(uint32_t n, uint64_t seed, bool scrambled) {
  if (Status s = CheckSampleCount(scrambled ? "hammersley-scrambled" : "hammersley", n); !s.ok()) {
    return s;
  }
  const DigitPermutations py(2, HashCombine(seed, 13));
  PointSet points(n);
  for (uint32_t i = 0; i < n; ++i) {
    points[i] = {static_cast<double>(i) / n, scrambled ? py.Apply(i) : RadicalInverse(2, i)};
  }
  return points;
}

StatusOr<PointSet> Sobol(uint32_t n) {
  if (Status s = CheckSampleCount("sobol", n); !s.ok()) return s;
  PointSet points(n);
  for (uint32_t i = 0; i < n; ++i) {
    points[i] = {FromFixed32(SobolDim0(i)), FromFixed32(SobolDim1(i))};
  }
  return points;
}

}  // namespace alignset

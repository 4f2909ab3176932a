#include <alignset/joint_lattice.h>

#include <cmath>
#include <numbers>
#include <numeric>
#include <string>

#include "core/sampling/owen_sobol.h"
#include "core/util/hash.h"

namespace alignset {
namespace {

constexpr uint64_t kSaltShift = 11;
constexpr uint64_t kSaltPad = 12;

// 2 pi^2 B_2(x), B_2 the Bernoulli polynomial x^2 - x + 1/6: the Korobov
// kernel of smoothness 2 at a lattice coordinate x in [0, 1).
double Kernel(double x) { return 2.0 * std::numbers::pi * std::numbers::pi * (x * x - x + 1.0 / 6.0); }

double Weight(size_t j) { return std::pow(kJointLatticeWeightDecay, static_cast<double>(j)); }

double Unit(uint64_t h) { return static_cast<double>(h >> 11) * 0x1.0p-53; }

}  // namespace

double JointLatticeP2(uint32_t n, const std::vector<uint32_t>& z) {
  double sum = 0.0;
  for (uint32_t k = 0; k < n; ++k) {
    double prod = 1.0;
    for (size_t j = 0; j < z.size(); ++j) {
      const uint32_t r = static_cast<uint32_t>((static_cast<uint64_t>(k) * z[j]) % n);
      prod *= 1.0 + Weight(j) * Kernel(static_cast<double>(r) / n);
    }
    sum += prod;
  }
  return sum / n - 1.0;
}

StatusOr<JointLattice> JointLattice::Create(uint32_t n, uint32_t dimensions, uint64_t seed) {
  if (n < 2 || n > 65536) return Status::InvalidArgument("joint lattice: N must be in [2, 65536], got " + std::to_string(n));
  if (dimensions < 1 || dimensions > kJointLatticeMaxDimensions) {
    return Status::InvalidArgument("joint lattice: dimensions must be in [1, " +
                                   std::to_string(kJointLatticeMaxDimensions) + "], got " +
                                   std::to_string(dimensions));
  }
  JointLattice l;
  l.n_ = n;
  l.seed_ = seed;
  l.z_.push_back(1);
  // Component by component: prod[k] holds the product over the chosen
  // components at point k, so each candidate costs one pass over the points.
  std::vector<double> prod(n), kernel(n);
  for (uint32_t k = 0; k < n; ++k) {
    kernel[k] = Kernel(static_cast<double>(k) / n);
    prod[k] = 1.0 + Weight(0) * kernel[k];
  }
  for (uint32_t j = 1; j < dimensions; ++j) {
    const double w = Weight(j);
    uint32_t best = 1;
    double best_sum = INFINITY;
    for (uint32_t c = 1; c <= n / 2; ++c) {  // c and n - c give the same criterion
      if (std::gcd(c, n) != 1) continue;
      double sum = 0.0;
      uint64_t r = 0;
      for (uint32_t k = 0; k < n; ++k, r += c) {
        if (r >= n) r -= n;
        sum += prod[k] * (1.0 + w * kernel[r]);
      }
      if (sum < best_sum) {
        best_sum = sum;
        best = c;
      }
    }
    l.z_.push_back(best);
    for (uint32_t k = 0; k < n; ++k) {
      prod[k] *= 1.0 + w * kernel[static_cast<uint32_t>((static_cast<uint64_t>(k) * best) % n)];
    }
  }
  return l;
}

double JointLattice::Shift(uint64_t pixel, uint32_t d) const {
  return Unit(Mix64(HashCombine(HashCombine(HashCombine(seed_, kSaltShift), pixel), d)));
}

double JointLattice::Sample(uint64_t pixel, uint32_t i, uint32_t d) const {
  if (d < z_.size()) {
    const uint32_t r = static_cast<uint32_t>((static_cast<uint64_t>(i) * z_[d]) % n_);
    double x = static_cast<double>(r) / n_ + Shift(pixel, d);
    if (x >= 1.0) x -= 1.0;
    return x;
  }
  // Padding: a 1-D Owen-scrambled Sobol point of its own scramble, its index
  // scrambled too, so that the padded dimensions pair at random.
  const uint64_t h = HashCombine(HashCombine(HashCombine(seed_, kSaltPad), pixel), d);
  const uint32_t index = NestedUniformScramble(i, static_cast<uint32_t>(h));
  const uint32_t v = NestedUniformScramble(SobolDim0(index), static_cast<uint32_t>(h >> 32));
  return static_cast<double>(v) * 0x1.0p-32;
}

}  // namespace alignset

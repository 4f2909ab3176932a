#pragma once

// A joint rank-1 lattice over a camera sample's leading dimensions (film x,
// film y, wavelength, the first light sample's two, ...): one point set a
// pixel, stratified jointly, where the 2-D sets of AlignedSampler pair their
// dimensions at random. The structure without an alignment: a per-pixel
// randomized rank-1 lattice, the baseline that an aligned joint lattice is
// measured against (what joint stratification alone is worth).
//
// The lattice: point i of N in D dimensions is frac(i z / N + s), z the
// generator, s the pixel's Cranley-Patterson shift (a hash of the seed, the
// pixel and the dimension). z is chosen once per (N, D) by the
// component-by-component construction on the weighted P_2 criterion (the
// worst-case error of a shifted lattice in the Korobov space of smoothness 2
// with product weights gamma_j = kJointLatticeWeightDecay^j, j from 0), so
// every leading projection of the lattice is a good lattice of its own: the
// film's 2-D set first, then film x wavelength, and so on. z_0 = 1, every z_j
// coprime to N: each 1-D projection is the N strata of [0, 1).
//
// The API speaks dimensions, as pbrt's samplers do: Sample(pixel, i, d) is
// dimension d of sample i of a pixel; d >= dimensions() is padded with a 1-D
// Owen-scrambled Sobol point, scrambled per (pixel, dimension). Every value
// is uniform on [0, 1) over the seed, so every estimate is unbiased;
// deterministic in (seed, pixel, i, d); no allocation after Create.

#include <alignset/status.h>

#include <cstdint>
#include <vector>

namespace alignset {

inline constexpr double kJointLatticeWeightDecay = 0.7;
inline constexpr uint32_t kJointLatticeMaxDimensions = 16;

class JointLattice {
 public:
  // N in [2, 65536] and 1 <= dimensions <= kJointLatticeMaxDimensions;
  // INVALID_ARGUMENT otherwise. The search costs O(dimensions N^2 / 2).
  static StatusOr<JointLattice> Create(uint32_t n, uint32_t dimensions, uint64_t seed);
  JointLattice() = default;

  uint32_t n() const { return n_; }
  uint32_t dimensions() const { return static_cast<uint32_t>(z_.size()); }
  const std::vector<uint32_t>& generator() const { return z_; }

  // Dimension d of sample i (< n) of pixel `pixel` (the renderer's pixel
  // index, e.g. y * width + x). No checks here (an inner loop).
  double Sample(uint64_t pixel, uint32_t i, uint32_t d) const;
  // The pixel's shift in lattice dimension d (< dimensions()).
  double Shift(uint64_t pixel, uint32_t d) const;

 private:
  uint32_t n_ = 0;
  uint64_t seed_ = 0;
  std::vector<uint32_t> z_;
};

// The weighted P_2 criterion of the rank-1 lattice of generator z with N
// points (the weights as above): smaller is better; 0 only for N -> infinity.
// Exposed for tests and benchmarks.
double JointLatticeP2(uint32_t n, const std::vector<uint32_t>& z);

}  // namespace alignset

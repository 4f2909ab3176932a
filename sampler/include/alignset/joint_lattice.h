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
// pixel and the dimension). z is chosen once per (N, D) component by
// component, in two stages: first every 2-D projection of the new component
// with an earlier one, by its shortest dual vector (a candidate's worst pair
// at least kJointLatticePairFloor, or kJointLatticePairSlack of the best
// candidate's worst where that is less: no projection on a few lines), then,
// among those, the weighted P_2 criterion (the worst-case error of a shifted
// lattice in the Korobov space of smoothness 2, product weights gamma_j =
// kJointLatticeWeightDecay^j, j from 0), which sees the higher-order
// projections too. Where that greedy order leaves a pair of the first four
// components (a renderer's film and light squares) below the floor (N = 32,
// 40, 44), the four are searched together for the largest worst pair, and
// the rest follow component by component. z_0 = 1, every z_j coprime to N:
// each 1-D projection is the N strata of [0, 1).
//
// The API speaks dimensions, as pbrt's samplers do: Sample(pixel, i, d) is
// dimension d of sample i of a pixel. The dimensions past the lattice are
// padded with one Sobol sequence indexed by i itself: d = dimensions() + k is
// Sobol dimension k of point i, Owen-scrambled per (pixel, dimension). A
// path's later bounces are then stratified jointly, as pbrt's "sobol"
// stratifies them, where 1-D points paired at random (the padding before)
// left their joint projections at Monte Carlo's rate: measured in pbrt at
// 1024 samples a pixel with "path", 1.13x less edge error on the Cornell
// box, 1.06x on the rect-lit room (docs/pbrt.md, "The padding"). Past
// kJointLatticeSobolDimensions, 1-D Owen-scrambled Sobol points paired at
// random. Every value is uniform on [0, 1) over the seed, so every estimate
// is unbiased; deterministic in (seed, pixel, i, d); no allocation after
// Create.
//
// A folded dimension: where the renderer's integrand along dimension d has
// period 1 / h (pbrt draws a sample's four wavelengths at u, u + 1/4, u + 1/2,
// u + 3/4, so its value depends on frac(4 u) alone), the lattice coordinate
// is v = frac(4 u) itself and Sample returns u = (v + j) / h, j in {0, ..., h
// - 1} uniform per (pixel, sample): the integrand sees the lattice
// coordinate, u stays uniform on [0, 1) (a renderer that reads u alone, as
// pbrt does for a dispersive surface's one wavelength, stays unbiased).
// Unfolded, the lattice coordinate's harmonics h, 2h, ... would be what the
// integrand reads, the criterion would not see them, and h k z (mod N)
// collapses onto N / gcd(h, N) values: measured 4.5x more edge error than
// the same lattice with the wavelength padded (docs/pbrt.md).

// The tent: a renderer's integrand is not periodic over the pixel (the
// film, the light square, the BSDF sample), and a shifted lattice
// integrates its periodic extension, which jumps at the square's borders. In
// a tented dimension the shifted coordinate x is mapped by phi(x) = 1 - |2x
// - 1| (phi keeps the uniform measure, so the estimate stays unbiased), as
// the tent-lattice construction does for 2-D sets
// (docs/method.md#folding-the-lattice-tent-folded-lattices): f o phi is
// continuous on the torus, and a smooth f's error falls faster than
// Owen-Sobol's. The price is on edges: f o phi holds an edge twice,
// mirrored. A folded dimension is not tented: the integrand is periodic in
// it already.

// The jitter: the shift moves every point of a dimension by the same amount,
// so a shifted lattice integrates a smooth non-periodic 1-D component (a
// pixel's radiance along the film x, a light square's falloff) at a stratum
// boundary's rate, N^-2 in variance. Jittered, the pixel's hash picks an
// integer offset c_d and each point is uniform within its stratum: point i
// is ((i z_d + c_d) mod N + u_{i,d}) / N, u uniform per (pixel, sample,
// dimension). Each 1-D projection is then stratified sampling (N^-3), and the
// lattice's 2-D structure moves by at most 1/N. Values stay uniform over the
// seed, so the estimate stays unbiased.
#include <alignset/status.h>

#include <cstdint>
#include <vector>

namespace alignset {

inline constexpr double kJointLatticeWeightDecay = 0.7;
inline constexpr double kJointLatticePairSlack = 0.8;
inline constexpr double kJointLatticePairFloor = 0.3;
inline constexpr uint32_t kJointLatticeMaxDimensions = 16;
// The padded dimensions that are one jointly indexed Sobol sequence (a
// depth-100 path in pbrt; 128 KiB of direction numbers, one table that every
// lattice shares).
inline constexpr uint32_t kJointLatticeSobolDimensions = 1024;

class JointLattice {
 public:
  // N in [2, 65536] and 1 <= dimensions <= kJointLatticeMaxDimensions;
  // INVALID_ARGUMENT otherwise. The search costs O(dimensions N^2 / 2).
  // folds[d] (absent: 1) is dimension d's h, 1 to 64; a longer `folds` than
  // `dimensions`, or an h outside 1..64, is INVALID_ARGUMENT. tents[d]
  // (absent: false): dimension d is tented after its shift; a longer `tents`
  // than `dimensions`, or a dimension both folded and tented, is
  // INVALID_ARGUMENT. jitter: every lattice dimension jittered within its
  // strata (above) instead of shifted.
  static StatusOr<JointLattice> Create(uint32_t n, uint32_t dimensions, uint64_t seed,
                                       const std::vector<uint32_t>& folds = {},
                                       const std::vector<bool>& tents = {}, bool jitter = false);
  JointLattice() = default;

  uint32_t n() const { return n_; }
  // The lattice's dimensions: those asked for, or fewer where a small N has
  // no component left but a repeat of an earlier one or its mirror (pbrt's
  // nine: 4 at N = 16, 8 at 32, all nine at 64 and from 128 on). Sample pads
  // the rest.
  uint32_t dimensions() const { return static_cast<uint32_t>(z_.size()); }
  const std::vector<uint32_t>& generator() const { return z_; }
  // Whether dimension d (< the dimensions asked for) is tented.
  bool tented(uint32_t d) const { return d < tents_.size() && tents_[d]; }
  bool jittered() const { return jitter_; }

  // Dimension d of sample i (< n) of pixel `pixel` (the renderer's pixel
  // index, e.g. y * width + x). No checks here (an inner loop). A renderer
  // that asks for many values of one pixel in a row is faster with a
  // JointLatticePixel (below), which returns the same values.
  double Sample(uint64_t pixel, uint32_t i, uint32_t d) const;
  // The pixel's shift in lattice dimension d (< dimensions()).
  double Shift(uint64_t pixel, uint32_t d) const;

 private:
  friend class JointLatticePixel;
  // The hashes a value is made from, per pixel (the shifts' and the fold's)
  // and per (pixel, padded dimension): a JointLatticePixel keeps them.
  uint64_t FoldKey(uint64_t pixel) const;
  uint64_t PaddingKey(uint64_t pixel, uint32_t d) const;
  // Lattice dimension d of sample i, the pixel's shift and fold key given.
  double LatticeValue(uint32_t i, uint32_t d, double shift, uint64_t fold_key) const;
  // Padded dimension d of sample i, its key given.
  double PaddingValue(uint32_t i, uint32_t d, uint64_t key) const;

  uint32_t n_ = 0;
  uint32_t mask_ = 0;  // N - 1 where N is a power of two (i z mod N a mask), else 0
  uint64_t seed_ = 0;
  std::vector<uint32_t> z_;
  std::vector<uint32_t> folds_;  // one per dimension asked for (1: not folded)
  std::vector<bool> tents_;      // one per dimension asked for
  bool jitter_ = false;
  // The padding's Sobol direction numbers, kSobolDigits a dimension: the
  // process's one table, made at the first Create.
  const uint32_t* padding_ = nullptr;
};

// One pixel's view of a JointLattice, for a renderer that asks for a pixel's
// values in a row (pbrt: up to 64 samples of a pixel, dozens of dimensions
// each). JointLattice::Sample hashes (seed, pixel, dimension) into the shift
// or the scramble for every value; the view makes the pixel's shifts once at
// Reset and each padded dimension's scramble key at its first use, so a
// value is a multiply and a shift (lattice) or the Sobol digits and one
// scramble (padding). Its values are JointLattice::Sample's bit for bit
// (tests/sampler/joint_lattice_test.cc). Holds no allocation; one per
// thread; the lattice must outlive it.
class JointLatticePixel {
 public:
  // The padded dimensions whose scramble keys the view keeps; past them,
  // each value is hashed as JointLattice::Sample does.
  static constexpr uint32_t kKeptPaddingKeys = 64;

  JointLatticePixel() = default;
  // Points the view at pixel `pixel` of `lattice`.
  void Reset(const JointLattice& lattice, uint64_t pixel);
  bool valid() const { return lattice_ != nullptr; }
  uint64_t pixel() const { return pixel_; }
  // JointLattice::Sample(pixel(), i, d). Not const: it keeps a padded
  // dimension's key on its first use.
  double Sample(uint32_t i, uint32_t d);

 private:
  const JointLattice* lattice_ = nullptr;
  uint64_t pixel_ = 0;
  uint64_t fold_key_ = 0;
  uint64_t kept_ = 0;  // bit k: padding_keys_[k] is made
  double shifts_[kJointLatticeMaxDimensions] = {};
  uint64_t padding_keys_[kKeptPaddingKeys] = {};
};

// The weighted P_2 criterion of the rank-1 lattice of generator z with N
// points (the weights as above): smaller is better; 0 only for N -> infinity.
// Exposed for tests and benchmarks.
double JointLatticeP2(uint32_t n, const std::vector<uint32_t>& z);

// The 2-D projection (a, b) of an N-point rank-1 lattice (gcd(a, N) = 1): its
// dual lattice's shortest nonzero vector, squared, over the Hermite bound
// (2 / sqrt 3) N. 1 is the best any N-point 2-D lattice reaches (hexagonal);
// near 0, the projection's points lie on a few lines.
double JointLatticePairSpacing(uint32_t n, uint32_t a, uint32_t b);

}  // namespace alignset

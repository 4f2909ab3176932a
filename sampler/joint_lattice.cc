#include <alignset/joint_lattice.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <numbers>
#include <numeric>
#include <string>

#include "core/sampling/owen_sobol.h"
#include "core/sampling/rank1_lattice.h"
#include "core/sampling/sobol_directions.h"
#include "core/util/hash.h"

namespace alignset {
namespace {

constexpr uint64_t kSaltShift = 11;
constexpr uint64_t kSaltPad = 12;
constexpr uint64_t kSaltFold = 13;
constexpr uint32_t kMaxFold = 64;
static_assert(kJointLatticeSobolDimensions <= kSobolMaxDimensions);
// The joint search of the first four components costs up to (N / 2)^2 N
// pair spacings (pruned); the greedy search needs it at N = 32, 40 and 44
// only, of every N from 8 to 2100 (pbrt's nine dimensions).
constexpr uint32_t kHeadSearchMaxN = 4096;

// 2 pi^2 B_2(x), B_2 the Bernoulli polynomial x^2 - x + 1/6: the Korobov
// kernel of smoothness 2 at a lattice coordinate x in [0, 1).
double Kernel(double x) { return 2.0 * std::numbers::pi * std::numbers::pi * (x * x - x + 1.0 / 6.0); }

// Every lattice pads with the same sequence: its direction numbers are made
// once for the process (thread-safe static initialisation), not per Create.
const std::vector<uint32_t>& PaddingDirections() {
  static const std::vector<uint32_t> table = SobolDirectionNumbers(kJointLatticeSobolDimensions);
  return table;
}

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

double JointLatticePairSpacing(uint32_t n, uint32_t a, uint32_t b) {
  // The dual lattice {h : h_0 a + h_1 b = 0 (mod N)} is, axes swapped, the
  // rank-1 lattice of generator -b a^-1 (mod N), whose shortest vector has
  // the length of its mirror's, b a^-1: core's Lagrange-Gauss reduction.
  const uint32_t g = static_cast<uint32_t>((static_cast<uint64_t>(b) * Rank1InverseMod(a, n)) % n);
  const double shortest = Rank1MinDistanceTimesN(n, g);
  return shortest * shortest * std::sqrt(3.0) / (2.0 * n);
}

namespace {

// Extends z (its first components chosen) to `dimensions` components, or
// fewer (the small-N stop below).
void ExtendGenerator(uint32_t n, uint32_t dimensions, std::vector<uint32_t>& z) {
  // Component by component, in two stages. First every 2-D projection with a
  // component before it: a candidate's worst pair spacing (the shortest dual
  // vector, what an edge or a smooth integrand of two dimensions sees) at
  // least kJointLatticePairFloor, or kJointLatticePairSlack of the best
  // candidate's where that is less. Then, among those, the least weighted
  // P_2 (all projections, higher orders included). P_2 alone let the light
  // square of N = 64 fall onto 3 lines (0.08; measured in pbrt: 1.8x more
  // edge error than zsobol at 64 spp, 3x more than with the floor). A
  // tighter first stage (the best pairs within 0.8) cost 1.3-1.5x at 256
  // spp: it leaves P_2 too few candidates for the projections of three and
  // more. prod[k] holds the product over the chosen components at point k,
  // so each candidate's P_2 costs one pass over the points.
  std::vector<double> prod(n), kernel(n), spacing;
  std::vector<uint32_t> candidates;
  for (uint32_t k = 0; k < n; ++k) {
    kernel[k] = Kernel(static_cast<double>(k) / n);
    prod[k] = 1.0;
    for (size_t j = 0; j < z.size(); ++j) {
      prod[k] *= 1.0 + Weight(j) * kernel[static_cast<uint32_t>((static_cast<uint64_t>(k) * z[j]) % n)];
    }
  }
  for (uint32_t j = static_cast<uint32_t>(z.size()); j < dimensions; ++j) {
    const double w = Weight(j);
    candidates.clear();
    spacing.clear();
    double best_spacing = 0.0;
    for (uint32_t c = 1; c <= n / 2; ++c) {  // c and n - c give the same lattice up to a mirror
      if (std::gcd(c, n) != 1) continue;
      double worst = INFINITY;
      for (size_t a = 0; a < z.size(); ++a) {
        worst = std::min(worst, JointLatticePairSpacing(n, z[a], c));
      }
      candidates.push_back(c);
      spacing.push_back(worst);
      best_spacing = std::max(best_spacing, worst);
    }
    const double bar = std::min(kJointLatticePairFloor, kJointLatticePairSlack * best_spacing);
    uint32_t best = 1;
    double best_sum = INFINITY;
    for (size_t m = 0; m < candidates.size(); ++m) {
      if (spacing[m] + 1e-9 < bar) continue;  // ties in, on every platform
      const uint32_t c = candidates[m];
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
    // No component left but a repeat of an earlier one, or its mirror (N = 16
    // has four candidates): the two coordinates would be one up to the shift,
    // so this dimension and the rest are padded, which pairs them at random.
    // A merely poor pair stays: stopping at spacing 0.15 (N = 64 at six of
    // pbrt's nine) cost 0.83-0.92x zsobol's whole-image error with path at
    // 64 spp, against 1.04-1.10x.
    if (std::any_of(z.begin(), z.end(), [&](uint32_t a) { return best == a || best == n - a; })) break;
    z.push_back(best);
    for (uint32_t k = 0; k < n; ++k) {
      prod[k] *= 1.0 + w * kernel[static_cast<uint32_t>((static_cast<uint64_t>(k) * best) % n)];
    }
  }
}

// The worst 2-D projection among the first k components of z.
double WorstPair(uint32_t n, const std::vector<uint32_t>& z, size_t k) {
  double worst = INFINITY;
  for (size_t a = 0; a < k; ++a) {
    for (size_t b = a + 1; b < k; ++b) worst = std::min(worst, JointLatticePairSpacing(n, z[a], z[b]));
  }
  return worst;
}

// Components 1-3 together (component 0 is 1): the largest worst pair
// spacing among the six pairs of the first four, ties to the least P_2;
// empty where nothing beats `floor`. A candidate is pruned as soon as one of
// its pairs falls below the best so far, which the greedy search's worst
// starts at; c and N - c mirror a coordinate, so the first three need only
// c <= N / 2.
std::vector<uint32_t> SearchHead(uint32_t n, double floor) {
  std::vector<uint32_t> units;
  for (uint32_t c = 1; c < n; ++c) {
    if (std::gcd(c, n) == 1) units.push_back(c);
  }
  auto fresh = [&](uint32_t c, std::initializer_list<uint32_t> earlier) {
    for (uint32_t a : earlier) {
      if (c == a || c == n - a) return false;
    }
    return true;
  };
  std::vector<uint32_t> best;
  double best_worst = floor, best_p2 = INFINITY;
  for (uint32_t a : units) {
    if (a > n / 2 || !fresh(a, {1})) continue;
    const double s1 = JointLatticePairSpacing(n, 1, a);
    if (s1 + 1e-9 < best_worst) continue;
    for (uint32_t b : units) {
      if (b > n / 2 || !fresh(b, {1, a})) continue;
      const double s2 = std::min({s1, JointLatticePairSpacing(n, 1, b), JointLatticePairSpacing(n, a, b)});
      if (s2 + 1e-9 < best_worst) continue;
      for (uint32_t c : units) {
        if (!fresh(c, {1, a, b})) continue;
        const double w = std::min({s2, JointLatticePairSpacing(n, 1, c), JointLatticePairSpacing(n, a, c),
                                   JointLatticePairSpacing(n, b, c)});
        if (w + 1e-9 < best_worst || (best.empty() && w <= floor + 1e-9)) continue;
        const double p2 = JointLatticeP2(n, {1, a, b, c});
        if (w > best_worst + 1e-9) {
          best_worst = w;
          best_p2 = INFINITY;
        }
        if (p2 < best_p2) {
          best_p2 = p2;
          best = {1, a, b, c};
        }
      }
    }
  }
  return best;
}

}  // namespace

StatusOr<JointLattice> JointLattice::Create(uint32_t n, uint32_t dimensions, uint64_t seed,
                                            const std::vector<uint32_t>& folds,
                                            const std::vector<bool>& tents, bool jitter) {
  if (n < 2 || n > 65536) return Status::InvalidArgument("joint lattice: N must be in [2, 65536], got " + std::to_string(n));
  if (dimensions < 1 || dimensions > kJointLatticeMaxDimensions) {
    return Status::InvalidArgument("joint lattice: dimensions must be in [1, " +
                                   std::to_string(kJointLatticeMaxDimensions) + "], got " +
                                   std::to_string(dimensions));
  }
  if (folds.size() > dimensions) {
    return Status::InvalidArgument("joint lattice: " + std::to_string(folds.size()) + " folds for " +
                                   std::to_string(dimensions) + " dimensions");
  }
  for (uint32_t h : folds) {
    if (h < 1 || h > kMaxFold) {
      return Status::InvalidArgument("joint lattice: a fold must be in [1, " + std::to_string(kMaxFold) +
                                     "], got " + std::to_string(h));
    }
  }
  if (tents.size() > dimensions) {
    return Status::InvalidArgument("joint lattice: " + std::to_string(tents.size()) + " tents for " +
                                   std::to_string(dimensions) + " dimensions");
  }
  for (size_t d = 0; d < tents.size() && d < folds.size(); ++d) {
    if (tents[d] && folds[d] != 1) {
      return Status::InvalidArgument("joint lattice: dimension " + std::to_string(d) +
                                     " is folded, so periodic, and cannot be tented too");
    }
  }
  JointLattice l;
  l.folds_.assign(dimensions, 1);
  std::copy(folds.begin(), folds.end(), l.folds_.begin());
  l.tents_.assign(dimensions, false);
  std::copy(tents.begin(), tents.end(), l.tents_.begin());
  l.jitter_ = jitter;
  l.n_ = n;
  l.mask_ = (n & (n - 1)) == 0 ? n - 1 : 0;
  l.seed_ = seed;
  l.padding_ = PaddingDirections().data();
  l.z_ = {1};
  ExtendGenerator(n, dimensions, l.z_);
  // The greedy search fixes the film square first and may leave the light
  // square nothing but a few lines: N = 32 put it at spacing 0.27 (the film
  // at 0.87), and soft shadows at 32 spp had 1.26x zsobol's error (1.45x
  // with the light square alone in the lattice). Where a pair of the first
  // four components is below the floor, they are searched together.
  if (l.z_.size() >= 4 && n <= kHeadSearchMaxN) {
    const double greedy = WorstPair(n, l.z_, 4);
    if (greedy + 1e-9 < kJointLatticePairFloor) {
      std::vector<uint32_t> head = SearchHead(n, greedy);
      if (!head.empty()) {
        ExtendGenerator(n, dimensions, head);
        l.z_ = head;
      }
    }
  }
  return l;
}

double JointLattice::Shift(uint64_t pixel, uint32_t d) const {
  return Unit(Mix64(HashCombine(HashCombine(HashCombine(seed_, kSaltShift), pixel), d)));
}

uint64_t JointLattice::FoldKey(uint64_t pixel) const {
  return HashCombine(HashCombine(seed_, kSaltFold), pixel);
}

uint64_t JointLattice::PaddingKey(uint64_t pixel, uint32_t d) const {
  return HashCombine(HashCombine(HashCombine(seed_, kSaltPad), pixel), d);
}

double JointLattice::LatticeValue(uint32_t i, uint32_t d, double shift, uint64_t fold_key) const {
  // Jittered, the shift's top digits pick the stratum offset and all its
  // bits (a hash of seed, pixel and dimension) key the point's place in its
  // stratum.
  const uint64_t iz = static_cast<uint64_t>(i) * z_[d] + (jitter_ ? static_cast<uint32_t>(shift * n_) : 0);
  const uint32_t r = static_cast<uint32_t>(mask_ != 0 ? iz & mask_ : iz % n_);
  double x;
  if (jitter_) {
    const double u = Unit(Mix64(HashCombine(std::bit_cast<uint64_t>(shift), i)));
    x = std::min((static_cast<double>(r) + u) / n_, std::nextafter(1.0, 0.0));
  } else {
    x = static_cast<double>(r) / n_ + shift;
    if (x >= 1.0) x -= 1.0;
  }
  const uint32_t h = folds_[d];
  if (h == 1) return tents_[d] ? std::min(1.0 - std::abs(2.0 * x - 1.0), std::nextafter(1.0, 0.0)) : x;
  // Which of the h copies: uniform per (pixel, sample), independent of x.
  const uint64_t j = Mix64(HashCombine(fold_key, i)) % h;
  const double u = (x + static_cast<double>(j)) / h;
  return u < 1.0 ? u : std::nextafter(1.0, 0.0);
}

double JointLattice::PaddingValue(uint32_t i, uint32_t d, uint64_t key) const {
  const size_t k = d - z_.size();
  if (k < kJointLatticeSobolDimensions) {
    // Padding: Sobol dimension k of point i, its own scramble.
    const uint32_t v = NestedUniformScramble(SobolDigits(&padding_[k * kSobolDigits], i), static_cast<uint32_t>(key >> 32));
    return static_cast<double>(v) * 0x1.0p-32;
  }
  // Past the sequence's dimensions: a 1-D Owen-scrambled Sobol point of its
  // own scramble, its index scrambled too (paired at random).
  const uint32_t index = NestedUniformScramble(i, static_cast<uint32_t>(key));
  const uint32_t v = NestedUniformScramble(SobolDim0(index), static_cast<uint32_t>(key >> 32));
  return static_cast<double>(v) * 0x1.0p-32;
}

double JointLattice::Sample(uint64_t pixel, uint32_t i, uint32_t d) const {
  if (d < z_.size()) return LatticeValue(i, d, Shift(pixel, d), folds_[d] == 1 ? 0 : FoldKey(pixel));
  return PaddingValue(i, d, PaddingKey(pixel, d));
}

void JointLatticePixel::Reset(const JointLattice& lattice, uint64_t pixel) {
  lattice_ = &lattice;
  pixel_ = pixel;
  fold_key_ = lattice.FoldKey(pixel);
  kept_ = 0;
  for (uint32_t d = 0; d < lattice.dimensions(); ++d) shifts_[d] = lattice.Shift(pixel, d);
}

double JointLatticePixel::Sample(uint32_t i, uint32_t d) {
  const uint32_t lattice_dimensions = lattice_->dimensions();
  if (d < lattice_dimensions) return lattice_->LatticeValue(i, d, shifts_[d], fold_key_);
  const uint32_t k = d - lattice_dimensions;
  if (k >= kKeptPaddingKeys) return lattice_->PaddingValue(i, d, lattice_->PaddingKey(pixel_, d));
  const uint64_t bit = uint64_t{1} << k;
  if (!(kept_ & bit)) {
    padding_keys_[k] = lattice_->PaddingKey(pixel_, d);
    kept_ |= bit;
  }
  return lattice_->PaddingValue(i, d, padding_keys_[k]);
}

}  // namespace alignset

#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "render/pixel_integrand.h"
#include "render/scene.h"

namespace alignset::render {

// What a pixel's integrand says about the set to ask for. θ in degrees, in
// the spectral convention (the normal of the edge), in [0, 180).
struct PixelDirection {
  enum class Kind : int { kNone = 0, kOne = 1, kTwo = 2 };
  Kind kind = Kind::kNone;  // kNone: no dominant direction (smooth, or no clear edge)
  double theta1 = 0.0;
  double theta2 = 0.0;      // only for kTwo
  double kappa = 0.0;       // the estimator's concentration (0 for the geometry)
  double confidence = 0.0;  // share of the edge weight (geometry) or energy (estimator) in theta1
  // The pre-pass's own estimate of the pixel's integral, when the pre-pass
  // is one whose mean may be reused (prepass_samples > 0; Prepass::
  // Reusable) in the pixel's estimate (render/prepass_reuse.h). Kept for a
  // direction-less pixel too.
  double prepass_mean = 0.0;
  uint32_t prepass_samples = 0;
  // The scramble of those samples: they are the first prepass_samples points
  // of OwenScrambledSobol(·, prepass_seed), so a sampler can continue the
  // sequence (render/prepass_reuse.h), or, with prepass_lattice, the shift of
  // PrepassLatticePoints(prepass_samples, prepass_seed).
  uint64_t prepass_seed = 0;
  // Whether those samples are the pre-pass lattice of render/prepass_lattice.h
  // rather than Owen-Sobol points.
  bool prepass_lattice = false;
};

// d's direction with `from`'s pre-pass (mean, count, seed and kind): what a
// later stage that replaces a pixel's direction keeps.
inline PixelDirection WithPrepassOf(PixelDirection d, const PixelDirection& from) {
  d.prepass_mean = from.prepass_mean;
  d.prepass_samples = from.prepass_samples;
  d.prepass_seed = from.prepass_seed;
  d.prepass_lattice = from.prepass_lattice;
  return d;
}

// The bound: the direction from the scene's geometry. The pixel's
// discontinuities (PixelIntegrand::Discontinuities) are grouped by normal
// (pieces within kSameDirectionDeg are one direction), each group weighted by
// sum of length x jump; θ1 is the heaviest. A second group at least
// kSecondDirectionMinDeg away from θ1 and at least kSecondDirectionShare of
// θ1's weight makes the pixel kTwo.
inline constexpr double kSameDirectionDeg = 0.5;
inline constexpr double kSecondDirectionMinDeg = 2.0;
inline constexpr double kSecondDirectionShare = 0.25;
PixelDirection GeometryDirection(const PixelIntegrand& f);
std::vector<PixelDirection> GeometryDirections(const Scene& scene);

// The estimator slot: turns a low-spp pre-pass of a pixel's integrand into a
// direction, as a renderer that does not know its geometry must.
class DirectionEstimator {
 public:
  virtual ~DirectionEstimator() = default;
  virtual std::string name() const = 0;
  // Integrand evaluations the pre-pass spends per pixel.
  virtual int evaluations() const = 0;
  virtual PixelDirection Estimate(const PixelIntegrand& f, uint64_t pixel_seed) const = 0;
  // Pre-passes the estimator refused (counted, never silent: such a pixel is
  // treated as direction-less).
  virtual int64_t refusals() const { return 0; }
  // Every pixel of a scene, pixel i's pre-pass seeded by HashCombine(seed,
  // i). By default each pixel on its own; an estimator that also reads its
  // neighbours' pre-passes overrides this.
  virtual std::vector<PixelDirection> EstimateScene(const Scene& scene, uint64_t seed, int threads) const;
};

// The estimator of record is core/analysis's (render/spectral_estimator.h).

std::vector<PixelDirection> EstimateDirections(const Scene& scene, const DirectionEstimator& e,
                                               uint64_t seed, int threads);

}  // namespace alignset::render

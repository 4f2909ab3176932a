#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "render/aligned_sets.h"
#include "render/direction.h"
#include "render/pixel_integrand.h"
#include "core/sampling/screen_space_rank1.h"
#include "core/util/status.h"

namespace alignset::render {

// One pixel of one render: where it is and the render's seed (a different
// seed is an independent replicate of every randomization below).
struct PixelTask {
  int x = 0;
  int y = 0;
  size_t index = 0;  // y * width + x, into direction maps
  uint64_t seed = 1;
};

// Estimates a pixel's integral with N samples. Thread-safe (const).
class PixelSampler {
 public:
  virtual ~PixelSampler() = default;
  virtual double Estimate(const PixelIntegrand& f, const PixelTask& task) const = 0;
};

// Orientation of line and segment samples.
enum class LineOrientation {
  kNormal,  // along the estimated edge normal θ: the line crosses the edge
  kEdge,    // along the edge (θ + 90°)
  kRandom,  // one uniformly random direction per pixel
};

// Everything a sampler may need; each reads only its own fields.
struct SamplerConfig {
  SamplerConfig() = default;
  // The usual start: a sampler and its N, every other field its default.
  SamplerConfig(std::string sampler, uint32_t samples) : name(std::move(sampler)), n(samples) {}
  std::string name;
  uint32_t n = 0;
  // Directions per pixel (index y * W + x): `estimated` steers aligned,
  // pmj02bn-sheared, line and segment; `exact` steers the *-exact variants.
  const std::vector<PixelDirection>* estimated = nullptr;
  const std::vector<PixelDirection>* exact = nullptr;
  const RenderSets* sets = nullptr;        // aligned*, aligned-lattice*
  AlignedPolicy policy;                    // aligned*, aligned-lattice*
  bool per_pixel_shift = true;             // aligned: a CP shift per pixel (off: an ablation)
  const ShiftTile* tile = nullptr;         // screen-space-rank1
  LineOrientation orientation = LineOrientation::kNormal;  // line, segment
  double segment_length = 0.5;             // segment, in pixel widths
  int pool = 64;                           // pooled samplers: distinct sets per N
  // The samplers that read `estimated` add each pixel's randomized pre-pass
  // to their estimate (render/prepass_reuse.h); the others ignore it. With
  // continue_prepass, aligned and aligned-lattice (policy none = Owen-Sobol)
  // continue the pre-pass's sequence on a direction-less pixel
  // (ContinuedPrepass) instead of weighting two independent sets.
  bool reuse_prepass = false;
  bool continue_prepass = true;
};

// Builds a sampler by name:
//  - every name of `alignset sample --list`. Per-pixel decorrelation: random,
//    owen-sobol and the other cheap randomized samplers get a set of their
//    own per pixel (seed = hash of render seed and pixel); pmj02, pmj02bn
//    and the Poisson disk samplers, too slow to build per pixel, use a pool
//    of `pool` sets plus a per-pixel Cranley-Patterson shift (pbrt-v4's
//    recipe for pmj02bn); the deterministic ones (grid, halton, hammersley,
//    sobol) one set plus a per-pixel CP shift; hammersley-scrambled, whose
//    x = i / N is not random, a set per pixel plus a CP shift.
//  - pmj02bn-sheared, pmj02bn-sheared-exact: a pooled pmj02bn set sheared to
//    the pixel's θ (Algorithm 2), then CP-shifted; no shear without a direction.
//  - screen-space-rank1: Belcour and Heitz's rank-1 lattice screen-space
//    sampler on `tile`.
//  - aligned, aligned-exact: the set of `sets` for the pixel's estimated or
//    exact direction (ChooseSet under `policy`), CP-shifted per pixel.
//  - aligned-lattice, aligned-lattice-exact: the same recipe over a table of
//    aligned rank-1 lattices (render/lattice_sets.h) instead of fetched sets.
//  - line, segment: line and segment samples (Singh, Miller and Jarosz) in
//    `orientation`.
// INVALID_ARGUMENT for an unknown name, a missing input, or an N the
// sampler cannot honour.
StatusOr<std::unique_ptr<PixelSampler>> MakePixelSampler(const SamplerConfig& config);

// Whether the sampler `c` builds steers by the estimated direction map (and
// so pays for its pre-pass).
bool ReadsEstimatedDirections(const SamplerConfig& c);

// The names MakePixelSampler knows beyond the registry's.
std::vector<std::string> RenderSamplerNames();

// The per-pixel hash every randomization derives from.
uint64_t PixelHash(uint64_t seed, int x, int y, uint64_t salt);
// Two uniform numbers in [0,1) from a hash (a CP shift).
Point2 HashShift(uint64_t h);

// Line samples (Singh, Miller and Jarosz, "Variance and Convergence Analysis
// of Monte Carlo Line and Segment Sampling"): N chords of the pixel along the direction at
// `line_deg` (the line's own direction), at jittered offsets across it; each
// chord integrates f exactly. Unbiased: I = int dt int f ds, with t spread
// over the projection of the unit square on the chords' normal.
double LineEstimate(const PixelIntegrand& f, uint32_t n, double line_deg, uint64_t h);

// Segment samples: N segments of `length` centred at an Owen-scrambled Sobol
// set (seeded by h), along `segment_deg`, each integrating the pixel's
// periodic repetition exactly (divided by its length). Unbiased for any
// centres uniform on the torus: a box filter along the segment preserves the
// integral of a periodic function.
double SegmentEstimate(const PixelIntegrand& f, uint32_t n, double segment_deg, double length,
                       uint64_t h);

}  // namespace alignset::render

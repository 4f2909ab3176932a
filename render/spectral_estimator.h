#pragma once

#include <memory>
#include <string>

#include "render/direction.h"
#include "core/util/status.h"

namespace alignset::render {

// How far nedgesM's stack reaches on a shared domain: the (2R + 1)^2 pixels
// around the pixel, R = 1 unless a suffix sR asks for more. A neighbour
// sees the same edges at another offset, so more of them place the edges
// better, most of all the two of a corner, which the pixel's own 64
// samples rarely separate; but a farther neighbour also sees them turned a
// little more (the occluder's projection tilts with the receiver point),
// which costs where the set is most sensitive to the angle. Aligned
// lattices' edge error on the shadow scene against R = 1
// (bench/results/render_stack_radius.md): at N = 256 + 64 (seeds 1-6)
// -5.1% at R = 2 (every seed, -2.0 to -8.9%), -5.9% at R = 3, -7.3% at
// R = 4; at 1024 + 256 (seeds 1-3) -3.9% at R = 2 and -3.1% at R = 3; at
// 4096 + 256 +2.0% at R = 2 (-0.5 to +5.9%). The fit's time grows with the
// block (M = 64, 16384 pixels, two threads: 3.7, 8.6, 15.5, 23.6 s for
// R = 1..4, when each block found its pixels' crossings again; found once
// per pixel, R = 2 takes 6.3 s, and M = 256 16.4 s instead of 25-27 s; with
// 24 candidate directions, kStackedCandidates in the .cc, 2.2 and 4.6-6 s).
// AutoPrepass takes R = 2 up to N = 1024.
inline constexpr int kDefaultStackRadius = 1;
inline constexpr int kMaxStackRadius = 4;

// The estimator of record for the `aligned` sampler: a low-spp pre-pass of
// the pixel's integrand handed to core/analysis's EstimateDirection (issue
// 12: windowed patch power spectrum, line energy, von Mises fit, contrast
// test, optional second lobe). A pixel the estimator calls direction-less is
// kNone; a found second lobe makes it kTwo.
//
// The pre-pass, as a renderer without the geometry could take it:
//  - "gridG":    f at the cell centres of a G x G grid (G*G evaluations), the
//                estimator's grid path (one FFT);
//  - "jgridG":   one uniform random sample per cell of a G x G grid, its
//                value given to the cell (a jittered pre-pass), grid path;
//  - "samplesM": M Owen-scrambled Sobol points over the pixel (the
//                renderer's own low-spp pass), the scattered path (type-1
//                NUFFT, Monte Carlo noise floor and significance test);
//  - "edgesM":   the same M points, the direction from the line through
//                the midpoints of neighbouring samples whose values jump
//                (core/analysis/edge_line_fit.h): on a straight step 0.5°
//                median at M = 256 where the scattered spectral path is 20°
//                (bench/results/direction_accuracy.txt);
//  - "nedgesM":  the same M points per pixel, and the edge-line fit on the
//                samples of the pixel and of its neighbours (a renderer has
//                its neighbours' pre-pass too): where pixels are footprints
//                in the image plane, the samples within half a pixel (about
//                4M), looking only for lines that cross the pixel; where
//                every pixel integrates over one shared square (the shadow's
//                light, Scene::domain()), the 3 x 3 pixels' samples stacked
//                (a suffix sR: the (2R + 1)^2 around it), one parallel line
//                each (EstimateEdgeLinesStacked); the
//                pixel's own fit where that finds nothing or, on
//                footprints, where the two disagree by more than 8
//                degrees. The pixel pays M evaluations, as with edgesM,
//                and reuses its own M. Pooling
//                needs the scene (DirectionEstimator::EstimateScene); one
//                pixel's Estimate alone is edgesM's fit.
// A suffix "cP" (grid16c50) adds the renderer's own floor on the estimator's
// confidence (the share of the weight in the fitted lobe, here P percent):
// below it the pixel is treated as direction-less (the first lobe's; a
// found second lobe is kept).
//
// Only samplesM and edgesM are reusable in the pixel's estimate
// (render/prepass_reuse.h): their mean is an Owen-Sobol estimate of the
// pixel (with the suffix l, a shifted lattice's, as unbiased). gridG's is biased (the
// cell centres); jgridG's is unbiased but, measured on the scenes' pixels
// at 256 samples (tests/render/prepass_reuse_test.cc), 2-2.5 times
// Owen-Sobol's squared error on edges and 10^3 times on smooth pixels, and a
// grid shifted as a whole by one random offset, which would keep the grid
// path, errs to first order in the offset on a pixel that is not periodic
// (20 and 10^5 times), so neither is offered for reuse.
struct Prepass {
  enum class Kind { kGrid, kJitteredGrid, kSamples, kEdgeLines, kPooledEdgeLines };
  Kind kind = Kind::kGrid;
  int count = 16;            // the grid side G, or the sample count M
  int min_confidence_pct = 0;
  int stack_radius = kDefaultStackRadius;  // nedgesM on a shared domain
  // A suffix "l" on a scattered pre-pass: its M points are the pre-pass
  // lattice of render/prepass_lattice.h instead of Owen-Sobol points.
  bool lattice = false;
  std::string Name() const;
  bool Scattered() const {
    return kind == Kind::kSamples || kind == Kind::kEdgeLines || kind == Kind::kPooledEdgeLines;
  }
  int Evaluations() const { return Scattered() ? count : count * count; }
  // Whether the mean of the pre-pass's values is handed on for reuse (see
  // above: the Owen-Sobol pre-passes).
  bool Reusable() const { return Scattered(); }
};

// INVALID_ARGUMENT for anything but gridG / jgridG (8 <= G <= 64) or
// samplesM / edgesM / nedgesM (16 <= M <= 4096), nedgesM with an optional
// sR (1 <= R <= kMaxStackRadius), each with an optional cP (0 <= P <= 100)
// after it, and the scattered ones with an optional l at the very end.
StatusOr<Prepass> ParsePrepass(const std::string& spec);

// The default pre-pass of the estimated samplers in the benchmarks: 256
// Owen-Sobol samples per pixel and the edge-line fit pooled with the
// neighbours'. edges256 (the pixel's own samples) made every estimated
// sampler's edge error lower than grid16c50 (the same 256 evaluations) on
// the three scene seeds at N = 256, 1024 and 4096, and pooling lowered
// aligned-lattice's by another 1.1-1.4x on antialias at 1024 and 4096 and,
// read stacked (the shadow's pixels share the light's square), on shadow
// from 2.50 and 3.15x below Owen-Sobol at the same total to 3.19 and 4.03x
// (docs/rendering.md, "Every sample counted"). Its
// samples are reusable. (Its confidence is the inliers' share, at least
// one half, so a c50 floor is a no-op.) The lattice pre-pass (nedges256l,
// render/prepass_lattice.h) is not the default here: with 256 samples
// before N = 256 a smooth pixel keeps only the sampler's own 256 points,
// 0.12x Owen-Sobol at 512 where the continued sequence is Owen-Sobol at 512.
inline constexpr const char* kDefaultPrepass = "nedges256";
// `alignset render`'s default, "auto": the pooled edge-line fit on a
// quarter of the sampler's N, at least 16 and at most 256 samples (nedges64
// at N = 256, nedges256 from N = 1024 on), stacked over 5 x 5 pixels (s2)
// up to N = 1024 and over 3 x 3 above (kDefaultStackRadius's
// measurements). The quarter was measured with the pixel's own samples on
// the three scene seeds with aligned lattices: at N = 256, edges64 is
// 1.7-2.1x below Owen-Sobol at the same total (320) where edges256 is
// 1.2-1.4x (at 512), and a sweep of 32, 64 and 128
// samples and of the lattice's window kept 64
// (bench/results/render_prepass_sweep256.md); at 1024 edges256 is ahead.
// With pooling, nedges64 at 256 is 2.5x (antialias) and 2.1x (shadow)
// below Owen-Sobol at 320, and a sweep with the stacked shadow fit over
// scene seeds 1-6 kept 64 (nedges32 at 288: 2.07 and 2.08x; nedges128 at
// 384: 2.15 and 1.84x; docs/rendering.md, "Every sample counted").
// The samples are the lattice pre-pass (suffix l, render/prepass_lattice.h,
// since 2026-11-28) up to N = 1024, and at every N where the pixels share
// their domain (the stacked fit): aligned lattices' edge MSE 0.96-0.98x of
// the Owen-Sobol pre-pass's at 256 + 64 (scene seeds 1-18, both scenes; the
// worst seeds against the best other sampler higher too), 0.95-0.99x at
// 1024 + 256, and on shadow 0.94-1.00x at 4096 + 256 (seeds 1-9, 13-18);
// on footprints at 4096 + 256 single scenes moved by up to 27% either way
// (antialias seed 3 from 1.14x the best other sampler to 0.90x), so there
// the pre-pass stays Owen-Sobol (docs/rendering.md, "Every sample counted").
inline constexpr const char* kAutoPrepass = "auto";
std::string AutoPrepass(uint32_t n, PixelDomain domain);
// Whether and how a pre-pass is folded into the pixel's estimate
// (render/prepass_reuse.h): kAuto, the default, whenever the pre-pass is
// reusable (the default one is), a direction-less pixel continuing the
// pre-pass's sequence; kOn the same but refuses a pre-pass that is not
// reusable; kUnbiased the count weights on every pixel (strictly unbiased,
// at a cost on smooth pixels); kOff not at all.
enum class PrepassReuse { kAuto, kOn, kUnbiased, kOff };
// "auto", "on", "unbiased", "off"; INVALID_ARGUMENT otherwise.
StatusOr<PrepassReuse> ParsePrepassReuse(const std::string& text);

std::unique_ptr<DirectionEstimator> MakeSpectralEstimator(const Prepass& prepass);

// The confidence floor alone: an estimate of the same pre-pass without a
// floor, made direction-less when its first lobe's confidence is below
// min_confidence_pct (what MakeSpectralEstimator does with the floor; lets a
// bench estimate once and compare floors).
PixelDirection ApplyConfidenceFloor(const PixelDirection& d, int min_confidence_pct);

}  // namespace alignset::render

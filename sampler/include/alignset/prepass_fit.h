#pragma once

// A pixel's edge direction(s) from a low-spp pre-pass, its own samples read
// together with its neighbours': the first half of the per-pixel recipe
// (<alignset/aligned_sampler.h> is the whole). A renderer that wants the
// direction alone (for its own sampler, a filter, a debug view) uses this.
//
// The pre-pass points of pixel (x, y) are a function of (seed, y * width + x):
// a rank-1 lattice of M points under a uniform shift (its samples lie more
// evenly than Owen-Sobol's, so an edge's crossings do too), or M
// Owen-scrambled Sobol points. The fit places a line through the midpoints
// of neighbouring samples whose values jump (core's edge-line fit):
//  - on footprints, over the samples of the 3 x 3 pixels within half a pixel
//    of the pixel, looking for lines through it; where that line and the
//    pixel's own fit disagree by more than 8 degrees the pixel's own stands;
//  - on a shared domain, over the (2R + 1)^2 pixels' crossings stacked on
//    the pixel's, one parallel line each; it wins over the pixel's own.
// A second line (a corner) needs 15% of the crossings.

#include <alignset/point_set.h>
#include <alignset/status.h>

#include <cstdint>
#include <memory>
#include <span>

namespace alignset {

// How neighbouring pixels' integration domains lie to each other.
//  - kFootprint: each pixel integrates its own square of the image plane (a
//    silhouette's antialiasing): a neighbour's samples lie beside the
//    pixel's.
//  - kShared: every pixel integrates over the same square (a pixel's 2-D
//    light sample on one area light): a neighbour's samples are stacked on
//    the pixel's.
enum class PixelDomain { kFootprint, kShared };

struct PrepassFitOptions {
  PixelDomain domain = PixelDomain::kFootprint;
  uint32_t image_width = 0;    // pixels per row (the pixel seeds are y * width + x)
  uint64_t seed = 1;           // a render's seed
  uint32_t prepass_samples = 64;  // M, in [16, 4096]
  bool lattice_points = true;  // the pre-pass a shifted lattice (else Owen-Sobol points)
  int stack_radius = 1;        // R of a shared domain's (2R + 1)^2 block, in [1, 4]
  int min_confidence_pct = 0;  // a fit whose first line holds less of the crossings has none
};

// The pre-pass lattice of a pixel whose pre-pass seed is `pixel_seed`
// (PrepassFit::PrepassSeed): the M = out.size() point rank-1 lattice of
// the Korobov generator for M, under a uniform shift drawn from the seed.
// Its mean is unbiased; it is no net, so there is no sequence to continue.
void PrepassLatticePointsInto(uint64_t pixel_seed, std::span<Point2> out);

// What the fit found for one pixel.
struct FittedDirections {
  int directions = 0;          // 0, 1 or 2
  double theta1_deg = 0.0;     // the edge normals, degrees in [0, 180); theta1 the stronger
  double theta2_deg = 0.0;
  double confidence = 0.0;     // the first line's share of the crossings
  // A fit the core refused (counted, never silent: the pixel is then
  // direction-less, or keeps its own fit when only the pooled one failed).
  bool own_refused = false, pooled_refused = false;
};

class PrepassFit {
 public:
  // One per thread: the buffers a fit needs, and the crossings of the pixels
  // it read last (a raster walk reads most of a block again one pixel on; a
  // pixel's crossings are found again only when its values changed).
  class Scratch {
   public:
    Scratch();
    ~Scratch();
    Scratch(Scratch&&) noexcept;
    Scratch& operator=(Scratch&&) noexcept;

   private:
    friend class PrepassFit;
    struct Impl;
    std::unique_ptr<Impl> impl_;
  };

  // INVALID_ARGUMENT for options out of range.
  static StatusOr<PrepassFit> Create(const PrepassFitOptions& options);
  // An empty fit (what a failed Create holds); only Create makes one to use.
  PrepassFit() = default;

  const PrepassFitOptions& options() const { return options_; }
  uint32_t prepass_samples() const { return options_.prepass_samples; }
  int block_radius() const { return options_.domain == PixelDomain::kShared ? options_.stack_radius : 1; }
  int block_side() const { return 2 * block_radius() + 1; }

  // The pixel's pre-pass points (out.size() == prepass_samples()), and the
  // seed they derive from (an Owen-Sobol pre-pass is the first M points of
  // that seed's sequence, so a sampler can continue it).
  void PrepassPoints(uint32_t x, uint32_t y, std::span<Point2> out) const;
  uint64_t PrepassSeed(uint32_t x, uint32_t y) const;
  // The pixel's direction(s) from the pre-pass values of its block:
  // block_side()^2 spans, row by row from (x - R, y - R), each the M values
  // of that pixel in PrepassPoints order; an empty span for a pixel outside
  // the image. INVALID_ARGUMENT for a block of the wrong shape.
  StatusOr<FittedDirections> Fit(uint32_t x, uint32_t y, std::span<const std::span<const double>> block,
                                 Scratch& scratch) const;

 private:
  PrepassFitOptions options_;
};

}  // namespace alignset

#pragma once

#include <memory>
#include <string>

#include "render/direction.h"
#include "core/util/status.h"

namespace alignset::render {

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
//                NUFFT, Monte Carlo noise floor and significance test).
// A suffix "cP" (grid16c50) adds the renderer's own floor on the estimator's
// confidence (the share of the weight in the fitted lobe, here P percent):
// below it the pixel is treated as direction-less (the first lobe's; a
// found second lobe is kept). Measured on the scenes'
// pixels with grid16 (render_bench, README): a pure linear gradient is
// "found" with confidence 0.30-0.44 at an angle up to 34 degrees off its
// gradient, clean edges have a median of 0.75.
struct Prepass {
  enum class Kind { kGrid, kJitteredGrid, kSamples };
  Kind kind = Kind::kGrid;
  int count = 16;            // the grid side G, or the sample count M
  int min_confidence_pct = 0;
  std::string Name() const;
  int Evaluations() const { return kind == Kind::kSamples ? count : count * count; }
};

// INVALID_ARGUMENT for anything but gridG / jgridG (8 <= G <= 64) or
// samplesM (16 <= M <= 4096), each with an optional cP (0 <= P <= 100).
StatusOr<Prepass> ParsePrepass(const std::string& spec);

// The default pre-pass of `aligned` (README, "Rendered proof", measured
// against the others in bench/results/render_directions.txt).
inline constexpr const char* kDefaultPrepass = "grid16c50";

std::unique_ptr<DirectionEstimator> MakeSpectralEstimator(const Prepass& prepass);

// The confidence floor alone: an estimate of the same pre-pass without a
// floor, made direction-less when its first lobe's confidence is below
// min_confidence_pct (what MakeSpectralEstimator does with the floor; lets a
// bench estimate once and compare floors).
PixelDirection ApplyConfidenceFloor(const PixelDirection& d, int min_confidence_pct);

}  // namespace alignset::render

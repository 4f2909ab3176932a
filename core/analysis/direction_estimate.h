#pragma once

#include <string>

#include "core/analysis/patch_spectrum.h"
#include "core/spectral/spectral_engine.h"
#include "core/util/status.h"

namespace alignset {

// Principal-direction estimation (supplement Section 1, method.md §3): from
// an integrand, the direction theta whose line through the origin carries
// the most energy of its power spectrum, i.e. the normal of its dominant
// edge, the direction to ask the service for.
//
// 1. The power spectrum of the windowed, mean-free patch on a half disk
//    2 <= |v| <= R (PatchSpectrum: one FFT for a grid, a type-1 NUFFT of the
//    strengths for scattered samples).
// 2. Weights w_v = max(P(v) - t * floor, 0) |v|^beta: the sampling noise
//    floor removed (t = noise_threshold), and the edge's 1/|v|^2 fall-off
//    evened out so that every radius counts.
// 3. The angular distribution p: the line energy E(theta) of the weights
//    (AngularEnergy) at 2048 bins over [0, pi), less its median (the
//    isotropic floor), normalised, on doubled angles x = 2 theta (the data
//    are axial: P(v) = P(-v)).
// 4. A von Mises q(x | mu, kappa) fitted to p by gradient descent on
//    KL(q || p) + lambda kappa^2 (FitVonMises, Eqs. 1-4), from the highest
//    `starts` peaks of p; the fit with the lowest objective wins.
// 5. Refinement (on by default, measured better): the local maximum of
//    E(theta) within 1/sqrt(kappa) of mu / 2.
// 6. Confidence: the share of the weight within 1/sqrt(kappa) of theta (the
//    fitted lobe, two standard deviations of q). Contrast: the lobe's power
//    over what an isotropic spectrum with the same radial profile (every
//    frequency at its ring's mean power) would put in the same frequencies;
//    about 1 for noise or a disk on any lattice. Significance (scattered
//    samples): the lobe's excess over that null in standard deviations of
//    the Monte Carlo noise. Below min_contrast or min_significance the patch
//    has no dominant direction.
struct DirectionOptions {
  SpectrumOptions spectrum;   // window and radii
  double radial_power = -1.0; // beta; < 0: 2 for a grid, 1 for samples
  double noise_threshold = 4.0;
  double sigma = 1.0;         // line width of AngularEnergy, frequency units
  int bins = 2048;
  double lambda = 1e-4;
  double log_floor = 1e-3;    // p + log_floor / (2 pi) inside the log
  int starts = 3;
  bool refine = true;
  // The alternative to a window: leave out the frequencies within this many
  // degrees of 0° and 90° (0: keep them). Measured worse (docs/results.md, "Direction estimation").
  double axis_exclusion_deg = 0.0;
  // < 0: automatic, 1.7 for a grid and 2 for scattered samples.
  double min_contrast = -1.0;
  // Scattered samples only: the lobe's power must stand this many noise
  // standard deviations above the Monte Carlo noise floor.
  double min_significance = 5.0;
  bool second = false;        // also estimate a second direction
};

enum class DirectionStatus {
  kFound,
  kNoDominantDirection,  // constant, isotropic (noise, a disk), or too weak
};

// One lobe of the angular distribution.
struct DirectionLobe {
  DirectionStatus status = DirectionStatus::kNoDominantDirection;
  std::string reason;      // why there is none (empty when found)
  double theta_deg = 0.0;  // in [0, 180), spectral convention (edge normal)
  double fit_theta_deg = 0.0;  // mu / 2 of the von Mises fit, before refinement
  double kappa = 0.0;      // of the fit, on doubled angles
  double confidence = 0.0; // share of the weight in the lobe
  double contrast = 0.0;   // lobe power over the isotropic null's
  double significance = 0.0;  // lobe power over the noise floor, in noise sigmas (inf for grids)
  int fit_iterations = 0;
};

struct DirectionEstimate {
  DirectionLobe first;
  // With options.second: the strongest lobe left once the frequencies near
  // the first direction's line are taken out (confidence as a share of all
  // the weight).
  bool has_second = false;
  DirectionLobe second;
  double max_radius = 0.0;
  size_t frequencies = 0;
};

// Refuses invalid input (ValidateGridPatch / ValidateSampledPatch, bad
// options) with INVALID_ARGUMENT; a valid patch without a dominant direction
// is a result with status kNoDominantDirection, never a random angle.
StatusOr<DirectionEstimate> EstimateDirection(const GridPatch& patch,
                                              const DirectionOptions& options = {});
// engine: the spectral engine for the type-1 NUFFT (null: chosen by size).
StatusOr<DirectionEstimate> EstimateDirection(const SampledPatch& patch,
                                              const DirectionOptions& options = {},
                                              SpectralEngine* engine = nullptr);
// Steps 2-6 on a spectrum already computed; radial_power must be >= 0.
StatusOr<DirectionEstimate> EstimateDirectionFromSpectrum(const PatchSpectrum& spectrum,
                                                          const DirectionOptions& options);

Status ValidateDirectionOptions(const DirectionOptions& options);

}  // namespace alignset

#pragma once

#include <vector>

#include "core/spectral/frequency_set.h"
#include "core/spectral/spectral_engine.h"
#include "core/util/point_set.h"
#include "core/util/status.h"

namespace alignset {

// An integrand given as a regular grid over [0,1)^2: W columns along x, H
// rows along y, values[j * W + i] = f((i + 1/2) / W, (j + 1/2) / H) (row j,
// column i; y grows with the row index). A non-square grid still covers the
// unit square, so its angles are those of [0,1)^2, where the sets live.
struct GridPatch {
  int width = 0;
  int height = 0;
  std::vector<double> values;
};

// An integrand given as scattered samples f(points[j]) = values[j], e.g. a
// renderer's low-spp pre-pass; points in [0,1]^2, anywhere (not a grid).
struct SampledPatch {
  PointSet points;
  std::vector<double> values;
};

// Limits of what the estimator takes. A grid needs 8 <= W, H <= 4096 and at
// most 2^20 cells (a 1024 x 1024 patch, 8 MiB of doubles); scattered input
// 1 to 2^20 samples. More would not sharpen the estimate (the frequency
// radius is capped, see AutoMaxRadius) and only costs memory.
inline constexpr int kMinPatchSide = 8;
inline constexpr int kMaxPatchSide = 4096;
inline constexpr int64_t kMaxPatchCells = int64_t{1} << 20;
inline constexpr int64_t kMaxPatchSamples = int64_t{1} << 20;

// INVALID_ARGUMENT with a one-line reason for a grid of the wrong size,
// values that do not match width x height, or a non-finite value.
Status ValidateGridPatch(const GridPatch& patch);
// The size checks alone (before any value is copied).
Status ValidateGridSize(int64_t width, int64_t height);
// INVALID_ARGUMENT for no samples, too many, points and values of different
// counts, non-finite numbers, or a point outside [0,1]^2.
Status ValidateSampledPatch(const SampledPatch& patch);

// The Tukey window on [0,1]: 1 in the middle, a raised-cosine taper over a
// fraction taper/2 of the width at each end; taper 1 is the Hann window, 0 no
// window at all.
double TukeyWindow(double u, double taper);

struct SpectrumOptions {
  // Window fraction of the separable Tukey window w(x) w(y) multiplied onto
  // the patch (the non-periodic boundary would otherwise put energy along
  // 0° and 90°).
  double window_taper = 0.5;
  // Half disk of frequencies min_radius <= |v| <= max_radius (0: automatic).
  double min_radius = 2.0;
  double max_radius = 0.0;
};

// The automatic frequency radius. A grid: 7/16 of its shorter side (below
// the Nyquist radius, where aliasing of a point-sampled edge is worst), at
// most kMaxGridRadius. Samples: sqrt(M)/2 clamped to [6, 64], where an edge's
// 1/|v|^2 power falls to the Monte Carlo noise floor of M samples.
inline constexpr double kMaxGridRadius = 128.0;
double AutoMaxRadius(const GridPatch& patch);
double AutoMaxRadius(const SampledPatch& patch);

// The power spectrum of a patch: the mean-free, windowed integrand
//   g(s) = (f(s) - mean f) w(s_x) w(s_y)
// has F(v) = (1/M) sum_j g(s_j) exp(-2 pi i v.s_j) over its M cells or
// samples, and power |F(v)|^2, on the half disk (one of each +-v, since
// P(v) = P(-v)) in BuildFrequencySet's order.
struct PatchSpectrum {
  std::vector<Frequency> frequencies;
  std::vector<double> power;
  // The expected power of the sampling noise at every frequency: for
  // scattered samples the diagonal of |sum_j|^2, sum_j (g_j / M)^2 (random
  // positions make it a flat floor); 0 for a grid.
  double noise_floor = 0.0;
  // max |f - mean f| and max |f| over the input: a constant patch has a
  // deviation of 0, or of rounding size against the magnitude.
  double deviation = 0.0;
  double magnitude = 0.0;
  double max_radius = 0.0;
};

// A grid by one real-to-complex FFT of the W x H values (FFTW). The DFT of
// cell-centre samples equals the type-1 sum at the cell centres up to a
// phase, so the power is that of GridPowerSpectrumByEngine.
StatusOr<PatchSpectrum> GridPowerSpectrum(const GridPatch& patch, const SpectrumOptions& options);
// A grid through an engine's EvaluateWeighted with points at the cell
// centres (the same numbers; kept to test and time the FFT path against).
StatusOr<PatchSpectrum> GridPowerSpectrumByEngine(const GridPatch& patch,
                                                  const SpectrumOptions& options,
                                                  SpectralEngine* engine);
// Scattered samples through an engine's EvaluateWeighted (a type-1 NUFFT
// with the strengths g_j / M). engine null: a direct engine when M |K| is
// small, else a single-threaded fast engine.
StatusOr<PatchSpectrum> SampledPowerSpectrum(const SampledPatch& patch,
                                             const SpectrumOptions& options,
                                             SpectralEngine* engine);

}  // namespace alignset

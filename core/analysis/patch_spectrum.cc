#include "core/analysis/patch_spectrum.h"

#include <fftw3.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <memory>
#include <string>

#include "core/spectral/direct_engine.h"
#include "core/spectral/fast_engine.h"
#include "core/spectral/fftw_planner_lock.h"
#include "core/util/angles.h"

namespace alignset {
namespace {

// Below this many point-frequency pairs the direct engine is faster than
// setting up NUFFT grids.
constexpr double kDirectPairs = 1 << 22;

Status CheckOptions(const SpectrumOptions& o) {
  if (!std::isfinite(o.window_taper) || o.window_taper < 0.0 || o.window_taper > 1.0) {
    return Status::InvalidArgument("window taper must be in [0, 1]");
  }
  if (!std::isfinite(o.min_radius) || !std::isfinite(o.max_radius) || o.min_radius < 1.0 ||
      o.max_radius < 0.0 || o.max_radius > 1024.0) {
    return Status::InvalidArgument("frequency radii must be finite, min >= 1, max <= 1024");
  }
  return Status::Ok();
}

std::vector<Frequency> HalfAnnulus(double r_min, double r_max) {
  std::vector<Frequency> k = BuildFrequencySet({0.0, 0.0, r_max}, {});
  std::erase_if(k, [r_min](const Frequency& v) {
    return static_cast<double>(v.a) * v.a + static_cast<double>(v.b) * v.b < r_min * r_min;
  });
  return k;
}

double Resolve(double requested, double automatic) { return requested > 0.0 ? requested : automatic; }

// The windowed, mean-free strengths g_j / M of a grid, row-major; fills the
// deviation.
std::vector<double> GridStrengths(const GridPatch& patch, double taper, double* deviation,
                                  double* magnitude) {
  const int w = patch.width, h = patch.height;
  const size_t m = patch.values.size();
  double mean = 0.0;
  *magnitude = 0.0;
  for (double v : patch.values) {
    mean += v;
    *magnitude = std::max(*magnitude, std::fabs(v));
  }
  mean /= static_cast<double>(m);
  std::vector<double> wx(w), wy(h);
  for (int i = 0; i < w; ++i) wx[i] = TukeyWindow((i + 0.5) / w, taper);
  for (int j = 0; j < h; ++j) wy[j] = TukeyWindow((j + 0.5) / h, taper);
  std::vector<double> g(m);
  *deviation = 0.0;
  for (int j = 0; j < h; ++j) {
    for (int i = 0; i < w; ++i) {
      const double d = patch.values[static_cast<size_t>(j) * w + i] - mean;
      *deviation = std::max(*deviation, std::fabs(d));
      g[static_cast<size_t>(j) * w + i] = d * wx[i] * wy[j] / static_cast<double>(m);
    }
  }
  return g;
}

}  // namespace

Status ValidateGridSize(int64_t width, int64_t height) {
  if (width < kMinPatchSide || height < kMinPatchSide) {
    return Status::InvalidArgument("a grid patch needs at least " + std::to_string(kMinPatchSide) +
                                   " x " + std::to_string(kMinPatchSide) + " cells, got " +
                                   std::to_string(width) + " x " + std::to_string(height));
  }
  if (width > kMaxPatchSide || height > kMaxPatchSide || width * height > kMaxPatchCells) {
    return Status::InvalidArgument(
        "a grid patch may have at most " + std::to_string(kMaxPatchSide) + " cells a side and " +
        std::to_string(kMaxPatchCells) + " in all, got " + std::to_string(width) + " x " +
        std::to_string(height));
  }
  return Status::Ok();
}

Status ValidateGridPatch(const GridPatch& patch) {
  if (Status s = ValidateGridSize(patch.width, patch.height); !s.ok()) return s;
  const size_t want = static_cast<size_t>(patch.width) * patch.height;
  if (patch.values.size() != want) {
    return Status::InvalidArgument("a " + std::to_string(patch.width) + " x " +
                                   std::to_string(patch.height) + " grid needs " +
                                   std::to_string(want) + " values, got " +
                                   std::to_string(patch.values.size()));
  }
  for (size_t i = 0; i < patch.values.size(); ++i) {
    if (!std::isfinite(patch.values[i])) {
      return Status::InvalidArgument("grid value " + std::to_string(i) + " (row " +
                                     std::to_string(i / patch.width) + ", column " +
                                     std::to_string(i % patch.width) + ") is not finite");
    }
  }
  return Status::Ok();
}

double TukeyWindow(double u, double taper) {
  if (taper <= 0.0) return 1.0;
  const double edge = 0.5 * taper;
  const double t = std::min(u, 1.0 - u);
  if (t >= edge) return 1.0;
  if (t <= 0.0) return 0.0;
  return 0.5 - 0.5 * std::cos(kPi * t / edge);
}

double AutoMaxRadius(const GridPatch& patch) {
  return std::min(kMaxGridRadius, std::floor(7.0 / 16.0 * std::min(patch.width, patch.height)));
}

double AutoMaxRadius(const SampledPatch& patch) {
  return std::clamp(std::round(0.5 * std::sqrt(static_cast<double>(patch.points.size()))), 6.0,
                    64.0);
}

StatusOr<PatchSpectrum> GridPowerSpectrum(const GridPatch& patch, const SpectrumOptions& options) {
  if (Status s = ValidateGridPatch(patch); !s.ok()) return s;
  if (Status s = CheckOptions(options); !s.ok()) return s;
  PatchSpectrum out;
  out.max_radius = Resolve(options.max_radius, AutoMaxRadius(patch));
  if (2.0 * out.max_radius >= std::min(patch.width, patch.height)) {
    return Status::InvalidArgument("max radius " + std::to_string(out.max_radius) +
                                   " reaches the grid's Nyquist limit");
  }
  out.frequencies = HalfAnnulus(options.min_radius, out.max_radius);
  std::vector<double> g = GridStrengths(patch, options.window_taper, &out.deviation, &out.magnitude);

  const int w = patch.width, h = patch.height, wc = w / 2 + 1;
  double* in = fftw_alloc_real(static_cast<size_t>(w) * h);
  fftw_complex* spec = fftw_alloc_complex(static_cast<size_t>(wc) * h);
  fftw_plan plan;
  {
    std::lock_guard<std::mutex> lock(FftwPlannerLock());
    plan = fftw_plan_dft_r2c_2d(h, w, in, spec, FFTW_ESTIMATE);
  }
  std::copy(g.begin(), g.end(), in);
  fftw_execute(plan);
  out.power.resize(out.frequencies.size());
  for (size_t k = 0; k < out.frequencies.size(); ++k) {
    // Row b (y), column a (x); the r2c output holds a >= 0, and the rest by
    // Hermitian symmetry F(-v) = conj F(v), which has the same power.
    int a = out.frequencies[k].a, b = out.frequencies[k].b;
    if (a < 0) {
      a = -a;
      b = -b;
    }
    const int row = ((b % h) + h) % h;
    const fftw_complex& c = spec[static_cast<size_t>(row) * wc + a];
    out.power[k] = c[0] * c[0] + c[1] * c[1];
  }
  {
    std::lock_guard<std::mutex> lock(FftwPlannerLock());
    fftw_destroy_plan(plan);
  }
  fftw_free(in);
  fftw_free(spec);
  return out;
}

namespace {

StatusOr<PatchSpectrum> EngineSpectrum(const PointSet& points, const std::vector<double>& strengths,
                                       PatchSpectrum out, SpectralEngine* engine) {
  std::unique_ptr<SpectralEngine> own;
  if (engine == nullptr) {
    const double pairs = static_cast<double>(points.size()) * out.frequencies.size();
    if (pairs <= kDirectPairs) {
      own = std::make_unique<DirectEngine>(1);
    } else {
      own = std::make_unique<FastEngine>(1);
    }
    engine = own.get();
  }
  engine->SetFrequencies(out.frequencies);
  std::vector<std::complex<double>> spectrum;
  engine->EvaluateWeighted(points, strengths, &spectrum);
  out.power.resize(spectrum.size());
  for (size_t k = 0; k < spectrum.size(); ++k) out.power[k] = std::norm(spectrum[k]);
  return out;
}

}  // namespace

StatusOr<PatchSpectrum> GridPowerSpectrumByEngine(const GridPatch& patch,
                                                  const SpectrumOptions& options,
                                                  SpectralEngine* engine) {
  if (Status s = ValidateGridPatch(patch); !s.ok()) return s;
  if (Status s = CheckOptions(options); !s.ok()) return s;
  PatchSpectrum out;
  out.max_radius = Resolve(options.max_radius, AutoMaxRadius(patch));
  if (2.0 * out.max_radius >= std::min(patch.width, patch.height)) {
    return Status::InvalidArgument("max radius " + std::to_string(out.max_radius) +
                                   " reaches the grid's Nyquist limit");
  }
  out.frequencies = HalfAnnulus(options.min_radius, out.max_radius);
  std::vector<double> g = GridStrengths(patch, options.window_taper, &out.deviation, &out.magnitude);
  PointSet points;
  points.reserve(g.size());
  for (int j = 0; j < patch.height; ++j) {
    for (int i = 0; i < patch.width; ++i) {
      points.push_back({(i + 0.5) / patch.width, (j + 0.5) / patch.height});
    }
  }
  return EngineSpectrum(points, g, std::move(out), engine);
}

StatusOr<PatchSpectrum> SampledPowerSpectrum(const SampledPatch& patch,
                                             const SpectrumOptions& options,
                                             SpectralEngine* engine) {
  if (Status s = ValidateSampledPatch(patch); !s.ok()) return s;
  if (Status s = CheckOptions(options); !s.ok()) return s;
  PatchSpectrum out;
  out.max_radius = Resolve(options.max_radius, AutoMaxRadius(patch));
  out.frequencies = HalfAnnulus(options.min_radius, out.max_radius);
  const size_t m = patch.points.size();
  double mean = 0.0;
  for (double v : patch.values) {
    mean += v;
    out.magnitude = std::max(out.magnitude, std::fabs(v));
  }
  mean /= static_cast<double>(m);
  std::vector<double> g(m);
  PointSet points(m);
  for (size_t j = 0; j < m; ++j) {
    const Point2& p = patch.points[j];
    const double d = patch.values[j] - mean;
    out.deviation = std::max(out.deviation, std::fabs(d));
    g[j] = d * TukeyWindow(p.x, options.window_taper) * TukeyWindow(p.y, options.window_taper) /
           static_cast<double>(m);
    out.noise_floor += g[j] * g[j];
    // 1 is 0 on the torus, and the window is 0 there anyway.
    points[j] = {Wrap01(p.x), Wrap01(p.y)};
  }
  return EngineSpectrum(points, g, std::move(out), engine);
}

}  // namespace alignset

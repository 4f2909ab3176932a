#include "render/spectral_estimator.h"

#include <algorithm>
#include <atomic>
#include <cstdlib>

#include "core/analysis/direction_estimate.h"
#include "core/analysis/edge_line_fit.h"
#include "core/sampling/owen_sobol.h"
#include "core/util/hash.h"

namespace alignset::render {

std::string Prepass::Name() const {
  const std::string floor = min_confidence_pct > 0 ? "c" + std::to_string(min_confidence_pct) : "";
  switch (kind) {
    case Kind::kGrid: return "grid" + std::to_string(count) + floor;
    case Kind::kJitteredGrid: return "jgrid" + std::to_string(count) + floor;
    case Kind::kSamples: return "samples" + std::to_string(count) + floor;
    case Kind::kEdgeLines: return "edges" + std::to_string(count) + floor;
  }
  return "?";
}

StatusOr<Prepass> ParsePrepass(const std::string& spec) {
  auto refuse = [&] {
    return Status::InvalidArgument("pre-pass must be gridG or jgridG (G in [8, 64]) or samplesM or "
                                   "edgesM (M in [16, 4096]), optionally followed by cP (a confidence "
                                   "floor of P percent), got '" + spec + "'");
  };
  // 1 to 5 digits, or -1.
  auto digits = [](const std::string& s) -> int {
    if (s.empty() || s.size() > 5) return -1;
    for (char ch : s) {
      if (ch < '0' || ch > '9') return -1;
    }
    return std::atoi(s.c_str());
  };
  Prepass p;
  std::string rest;
  int lo = 8, hi = 64;
  if (spec.rfind("jgrid", 0) == 0) {
    p.kind = Prepass::Kind::kJitteredGrid;
    rest = spec.substr(5);
  } else if (spec.rfind("grid", 0) == 0) {
    p.kind = Prepass::Kind::kGrid;
    rest = spec.substr(4);
  } else if (spec.rfind("edges", 0) == 0) {
    p.kind = Prepass::Kind::kEdgeLines;
    rest = spec.substr(5);
    lo = 16;
    hi = 4096;
  } else if (spec.rfind("samples", 0) == 0) {
    p.kind = Prepass::Kind::kSamples;
    rest = spec.substr(7);
    lo = 16;
    hi = 4096;
  } else {
    return refuse();
  }
  const size_t c = rest.find('c');
  p.count = digits(rest.substr(0, c));
  if (c != std::string::npos) {
    p.min_confidence_pct = digits(rest.substr(c + 1));
    if (p.min_confidence_pct < 0 || p.min_confidence_pct > 100) return refuse();
  }
  if (p.count < lo || p.count > hi) return refuse();
  return p;
}

std::string AutoPrepass(uint32_t n) {
  return "edges" + std::to_string(std::clamp<uint32_t>(n / 4, 16, 256));
}

StatusOr<PrepassReuse> ParsePrepassReuse(const std::string& text) {
  if (text == "auto") return PrepassReuse::kAuto;
  if (text == "on") return PrepassReuse::kOn;
  if (text == "unbiased") return PrepassReuse::kUnbiased;
  if (text == "off") return PrepassReuse::kOff;
  return Status::InvalidArgument("pre-pass reuse must be auto, on, unbiased or off, got '" + text +
                                 "'");
}

namespace {

PixelDirection FromEstimate(const DirectionEstimate& e, int min_confidence_pct) {
  PixelDirection d;
  if (e.first.status != DirectionStatus::kFound) return d;
  d.kind = PixelDirection::Kind::kOne;
  d.theta1 = e.first.theta_deg;
  d.kappa = e.first.kappa;
  d.confidence = e.first.confidence;
  // The floor is on the first lobe only: a second lobe's share of the weight
  // is small by nature (and a found second lobe is the estimator's verdict).
  if (e.has_second && e.second.status == DirectionStatus::kFound) {
    d.kind = PixelDirection::Kind::kTwo;
    d.theta2 = e.second.theta_deg;
  }
  return ApplyConfidenceFloor(d, min_confidence_pct);
}

class SpectralEstimator : public DirectionEstimator {
 public:
  explicit SpectralEstimator(const Prepass& p) : p_(p) {
    options_.second = true;
    lines_.second = true;
  }
  std::string name() const override {
    return std::string(p_.kind == Prepass::Kind::kEdgeLines ? "core/analysis EstimateEdgeLines, "
                                                            : "core/analysis EstimateDirection, ") +
           p_.Name();
  }
  int evaluations() const override { return p_.Evaluations(); }

  PixelDirection Estimate(const PixelIntegrand& f, uint64_t pixel_seed) const override {
    double mean = 0.0;
    const StatusOr<DirectionEstimate> e = Run(f, pixel_seed, &mean);
    // A valid pre-pass is never refused; should it be, the pixel gets what a
    // direction-less pixel gets rather than a made-up angle.
    PixelDirection d;
    if (e.ok()) {
      d = FromEstimate(*e, p_.min_confidence_pct);
    } else {
      refused_.fetch_add(1, std::memory_order_relaxed);
    }
    if (p_.Reusable()) {
      d.prepass_mean = mean;
      d.prepass_samples = static_cast<uint32_t>(p_.Evaluations());
      d.prepass_seed = pixel_seed;
    }
    return d;
  }
  int64_t refusals() const override { return refused_.load(); }

 private:
  // The pre-pass's values go to the estimator; their mean to *mean.
  StatusOr<DirectionEstimate> Run(const PixelIntegrand& f, uint64_t pixel_seed,
                                  double* mean) const {
    auto average = [](const std::vector<double>& v) {
      double s = 0.0;
      for (double x : v) s += x;
      return s / static_cast<double>(v.size());
    };
    if (p_.Scattered()) {
      SampledPatch s;
      s.points = OwenScrambledSobol(static_cast<uint32_t>(p_.count), pixel_seed);
      s.values.reserve(s.points.size());
      for (const Point2& q : s.points) s.values.push_back(f.Eval({q.x, q.y}));
      *mean = average(s.values);
      if (p_.kind == Prepass::Kind::kEdgeLines) return EstimateEdgeLines(s, lines_);
      return EstimateDirection(s, options_);
    }
    const int g = p_.count;
    const bool jitter = p_.kind == Prepass::Kind::kJitteredGrid;
    GridPatch grid{g, g, std::vector<double>(static_cast<size_t>(g) * g)};
    Pcg32 rng(pixel_seed);
    for (int j = 0; j < g; ++j) {
      for (int i = 0; i < g; ++i) {
        const double u = jitter ? rng.NextDouble() : 0.5, v = jitter ? rng.NextDouble() : 0.5;
        grid.values[static_cast<size_t>(j) * g + i] = f.Eval({(i + u) / g, (j + v) / g});
      }
    }
    *mean = average(grid.values);
    return EstimateDirection(grid, options_);
  }

  Prepass p_;
  DirectionOptions options_;
  EdgeLineOptions lines_;
  mutable std::atomic<int64_t> refused_{0};
};

}  // namespace

PixelDirection ApplyConfidenceFloor(const PixelDirection& d, int min_confidence_pct) {
  if (d.kind == PixelDirection::Kind::kNone || d.confidence * 100.0 >= min_confidence_pct) return d;
  PixelDirection none;
  none.prepass_mean = d.prepass_mean;
  none.prepass_samples = d.prepass_samples;
  none.prepass_seed = d.prepass_seed;
  return none;
}

std::unique_ptr<DirectionEstimator> MakeSpectralEstimator(const Prepass& prepass) {
  return std::make_unique<SpectralEstimator>(prepass);
}

}  // namespace alignset::render

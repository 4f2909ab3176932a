#include "render/spectral_estimator.h"

#include <algorithm>
#include <atomic>
#include <cstdlib>

#include <alignset/prepass_fit.h>

#include "core/analysis/direction_estimate.h"
#include "core/analysis/edge_line_fit.h"
#include "core/sampling/owen_sobol.h"
#include "core/util/hash.h"
#include "core/util/directions.h"
#include "render/prepass_lattice.h"
#include "render/parallel.h"

namespace alignset::render {

std::string Prepass::Name() const {
  std::string floor;
  if (kind == Kind::kPooledEdgeLines && stack_radius != kDefaultStackRadius) {
    floor.append("s").append(std::to_string(stack_radius));
  }
  if (min_confidence_pct > 0) floor.append("c").append(std::to_string(min_confidence_pct));
  if (lattice) floor.append("l");
  switch (kind) {
    case Kind::kGrid: return "grid" + std::to_string(count) + floor;
    case Kind::kJitteredGrid: return "jgrid" + std::to_string(count) + floor;
    case Kind::kSamples: return "samples" + std::to_string(count) + floor;
    case Kind::kEdgeLines: return "edges" + std::to_string(count) + floor;
    case Kind::kPooledEdgeLines: return "nedges" + std::to_string(count) + floor;
  }
  return "?";
}

StatusOr<Prepass> ParsePrepass(const std::string& spec) {
  auto refuse = [&] {
    return Status::InvalidArgument("pre-pass must be gridG or jgridG (G in [8, 64]) or samplesM, "
                                   "edgesM or nedgesM (M in [16, 4096]; nedgesM optionally followed by sR, "
                                   "a stack of (2R + 1)^2 pixels on a shared domain, R in [1, " +
                                   std::to_string(kMaxStackRadius) + "]), optionally followed by cP (a "
                                   "confidence floor of P percent), the scattered ones optionally ending in l "
                                   "(a lattice pre-pass), got '" + spec + "'");
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
  std::string body = spec;
  if (!body.empty() && body.back() == 'l') {
    p.lattice = true;
    body.pop_back();
  }
  if (body.rfind("jgrid", 0) == 0) {
    p.kind = Prepass::Kind::kJitteredGrid;
    rest = body.substr(5);
  } else if (body.rfind("grid", 0) == 0) {
    p.kind = Prepass::Kind::kGrid;
    rest = body.substr(4);
  } else if (body.rfind("nedges", 0) == 0) {
    p.kind = Prepass::Kind::kPooledEdgeLines;
    rest = body.substr(6);
    lo = 16;
    hi = 4096;
  } else if (body.rfind("edges", 0) == 0) {
    p.kind = Prepass::Kind::kEdgeLines;
    rest = body.substr(5);
    lo = 16;
    hi = 4096;
  } else if (body.rfind("samples", 0) == 0) {
    p.kind = Prepass::Kind::kSamples;
    rest = body.substr(7);
    lo = 16;
    hi = 4096;
  } else {
    return refuse();
  }
  const size_t c = rest.find('c');
  const size_t r = rest.find('s');
  if (r != std::string::npos) {
    if (p.kind != Prepass::Kind::kPooledEdgeLines || (c != std::string::npos && c < r)) return refuse();
    p.stack_radius = digits(rest.substr(r + 1, c == std::string::npos ? std::string::npos : c - r - 1));
    if (p.stack_radius < 1 || p.stack_radius > kMaxStackRadius) return refuse();
  }
  p.count = digits(rest.substr(0, std::min(r, c)));
  if (c != std::string::npos) {
    p.min_confidence_pct = digits(rest.substr(c + 1));
    if (p.min_confidence_pct < 0 || p.min_confidence_pct > 100) return refuse();
  }
  if (p.count < lo || p.count > hi) return refuse();
  if (p.lattice && !p.Scattered()) return refuse();
  return p;
}

std::string AutoPrepass(uint32_t n, PixelDomain domain) {
  const bool lattice = n <= 1024 || domain == PixelDomain::kShared;
  return "nedges" + std::to_string(std::clamp<uint32_t>(n / 4, 16, 256)) + (n <= 1024 ? "s2" : "") +
         (lattice ? "l" : "");
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

// A second line (a corner's other edge) needs 15% of the crossings, not the
// fit's default 25%: pooled or stacked, a corner's shorter edge still holds
// many of them. Aligned lattices' edge MSE with the auto pre-pass (nedgesM,
// stacked 5 x 5): at N = 256 + 64 (seeds 1-6) shadow -1.8% (every seed,
// 0.1-3.5%), antialias +0.1%; at 1024 + 256 (seeds 1-3) -1.5% on both
// scenes; at 4096 nothing changes (one-direction sets there); 0.08 was no
// better (bench/results/render_stack_radius.md). It holds for every
// edge-line fit here, the pixel's own (edgesM, and nedgesM's fallback)
// included; edgesM alone was not re-measured with it.
constexpr double kPrepassSecondLineShare = 0.15;  // the sampler library's pooled fit takes the same

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
    lines_.second_min_share = kPrepassSecondLineShare;
  }
  std::string name() const override {
    const bool lines =
        p_.kind == Prepass::Kind::kEdgeLines || p_.kind == Prepass::Kind::kPooledEdgeLines;
    return std::string(lines ? "core/analysis EstimateEdgeLines, " : "core/analysis EstimateDirection, ") +
           p_.Name();
  }
  int evaluations() const override { return p_.Evaluations(); }

  PixelDirection Estimate(const PixelIntegrand& f, uint64_t pixel_seed) const override {
    if (p_.Scattered()) {
      const SampledPatch s = Sample(f, pixel_seed);
      return Finish(Fit(s), Mean(s.values), pixel_seed);
    }
    double mean = 0.0;
    const StatusOr<DirectionEstimate> e = Grid(f, pixel_seed, &mean);
    return Finish(e, mean, pixel_seed);
  }
  int64_t refusals() const override { return refused_.load(); }

  std::vector<PixelDirection> EstimateScene(const Scene& scene, uint64_t seed, int threads) const override {
    if (p_.kind != Prepass::Kind::kPooledEdgeLines) {
      return DirectionEstimator::EstimateScene(scene, seed, threads);
    }
    // The pixel and its neighbours, as the sampler library fits them
    // (<alignset/prepass_fit.h>): on pixel footprints, the samples within
    // half a pixel and lines that cross the pixel; on a domain every pixel
    // shares (the shadow's light), the neighbours' patches stacked on the
    // pixel's, one line each, all parallel. Row by row, keeping the
    // pre-passes of the rows a fit reads only (y - R ... y + R), so that
    // memory stays a few rows of M values however large the image: rows[k]
    // holds row y - R + k, empty beyond the image.
    const bool shared = scene.domain() == PixelDomain::kShared;
    PrepassFitOptions fo;
    fo.domain = shared ? ::alignset::PixelDomain::kShared : ::alignset::PixelDomain::kFootprint;
    fo.image_width = static_cast<uint32_t>(scene.width());
    fo.seed = seed;
    fo.prepass_samples = static_cast<uint32_t>(p_.count);
    fo.lattice_points = p_.lattice;
    fo.stack_radius = p_.stack_radius;
    fo.min_confidence_pct = p_.min_confidence_pct;
    auto made = PrepassFit::Create(fo);
    if (!made.ok()) {  // ParsePrepass admits no such pre-pass
      refused_.fetch_add(static_cast<int64_t>(scene.size()), std::memory_order_relaxed);
      return std::vector<PixelDirection>(scene.size());
    }
    const PrepassFit fit = *made;
    const int radius = fit.block_radius(), side = fit.block_side();
    const int w = scene.width(), hgt = scene.height();
    std::vector<PixelDirection> out(scene.size());
    std::vector<std::vector<std::vector<double>>> rows(static_cast<size_t>(side));
    auto sample_row = [&](int y, size_t k) {
      std::vector<std::vector<double>>& row = rows[k];
      row.assign(static_cast<size_t>(w), {});
      ParallelFor(static_cast<size_t>(w), threads, [&](size_t x) {
        const PixelIntegrand& f = scene.Pixel(static_cast<size_t>(y) * w + x);
        PointSet points(fit.prepass_samples());
        fit.PrepassPoints(static_cast<uint32_t>(x), static_cast<uint32_t>(y), points);
        row[x].reserve(points.size());
        for (const Point2& q : points) row[x].push_back(f.Eval({q.x, q.y}));
      });
    };
    for (int k = radius; k < side; ++k) {
      if (k - radius < hgt) sample_row(k - radius, static_cast<size_t>(k));
    }
    for (int y = 0; y < hgt; ++y) {
      ParallelFor(static_cast<size_t>(w), threads, [&](size_t x) {
        thread_local PrepassFit::Scratch scratch;
        const size_t i = static_cast<size_t>(y) * w + x;
        std::vector<std::span<const double>> block(static_cast<size_t>(side * side));
        for (int k = 0; k < side * side; ++k) {
          const size_t r = static_cast<size_t>(k / side);
          const int u = static_cast<int>(x) + k % side - radius;
          if (!rows[r].empty() && u >= 0 && u < w) block[static_cast<size_t>(k)] = rows[r][static_cast<size_t>(u)];
        }
        auto e = fit.Fit(static_cast<uint32_t>(x), static_cast<uint32_t>(y), block, scratch);
        PixelDirection d;
        if (e.ok()) {
          refused_.fetch_add(e->own_refused + e->pooled_refused, std::memory_order_relaxed);
          d.kind = static_cast<PixelDirection::Kind>(e->directions);
          d.theta1 = e->theta1_deg;
          d.theta2 = e->theta2_deg;
          d.confidence = e->confidence;
        } else {
          refused_.fetch_add(1, std::memory_order_relaxed);
        }
        d.prepass_mean = Mean(rows[static_cast<size_t>(radius)][x]);
        d.prepass_samples = fit.prepass_samples();
        d.prepass_seed = fit.PrepassSeed(static_cast<uint32_t>(x), static_cast<uint32_t>(y));
        d.prepass_lattice = p_.lattice;
        out[i] = d;
      });
      for (size_t k = 0; k + 1 < static_cast<size_t>(side); ++k) rows[k] = std::move(rows[k + 1]);
      rows[static_cast<size_t>(side - 1)] = {};
      if (y + radius + 1 < hgt) sample_row(y + radius + 1, static_cast<size_t>(side - 1));
    }
    return out;
  }

 private:
  static double Mean(const std::vector<double>& v) {
    double s = 0.0;
    for (double x : v) s += x;
    return s / static_cast<double>(v.size());
  }

  // The scattered pre-passes: M Owen-Sobol points of the pixel (the pre-pass
  // lattice with the suffix l) and f there.
  SampledPatch Sample(const PixelIntegrand& f, uint64_t pixel_seed) const {
    SampledPatch s;
    s.points = p_.lattice ? PrepassLatticePoints(static_cast<uint32_t>(p_.count), pixel_seed)
                          : OwenScrambledSobol(static_cast<uint32_t>(p_.count), pixel_seed);
    s.values.reserve(s.points.size());
    for (const Point2& q : s.points) s.values.push_back(f.Eval({q.x, q.y}));
    return s;
  }

  StatusOr<DirectionEstimate> Fit(const SampledPatch& s) const {
    if (p_.kind == Prepass::Kind::kSamples) return EstimateDirection(s, options_);
    return EstimateEdgeLines(s, lines_);
  }

  // The grid pre-passes; their values' mean to *mean.
  StatusOr<DirectionEstimate> Grid(const PixelIntegrand& f, uint64_t pixel_seed, double* mean) const {
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
    *mean = Mean(grid.values);
    return EstimateDirection(grid, options_);
  }

  // A pixel's direction from its estimate, with what reuse needs.
  PixelDirection Finish(const StatusOr<DirectionEstimate>& e, double mean, uint64_t pixel_seed) const {
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
      d.prepass_lattice = p_.lattice;
    }
    return d;
  }

  Prepass p_;
  DirectionOptions options_;
  EdgeLineOptions lines_;
  mutable std::atomic<int64_t> refused_{0};
};

}  // namespace

PixelDirection ApplyConfidenceFloor(const PixelDirection& d, int min_confidence_pct) {
  if (d.kind == PixelDirection::Kind::kNone || d.confidence * 100.0 >= min_confidence_pct) return d;
  return WithPrepassOf(PixelDirection{}, d);
}

std::unique_ptr<DirectionEstimator> MakeSpectralEstimator(const Prepass& prepass) {
  return std::make_unique<SpectralEstimator>(prepass);
}

}  // namespace alignset::render

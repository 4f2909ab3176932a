// Accuracy and cost of the direction estimator (issue 12, "What it must
// show"). Every figure of docs/results.md's "Direction estimation" tables:
//   build/bench/direction_accuracy [--cases 500] > bench/results/direction_accuracy.txt
// Errors are axial (mod 180) in degrees. Angles and offsets are drawn from a
// fixed seed, so the output is reproducible; a case flagged "no dominant
// direction" counts as a 90° error in the percentiles and in the "none"
// column.
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "core/analysis/direction_estimate.h"
#include "core/analysis/edge_line_fit.h"
#include "core/analysis/patch_sampling.h"
#include "core/analysis/step_integrand.h"
#include "core/spectral/direct_engine.h"
#include "core/spectral/fast_engine.h"
#include "core/sampling/owen_sobol.h"
#include "core/util/angles.h"
#include "core/util/hash.h"

using namespace alignset;

namespace {

double AngleError(double est, double truth) {
  double d = std::fmod(std::fabs(est - truth), 180.0);
  return std::min(d, 180.0 - d);
}

double Percentile(std::vector<double> v, double q) {
  if (v.empty()) return NAN;
  std::sort(v.begin(), v.end());
  const double pos = q * (v.size() - 1);
  const size_t i = static_cast<size_t>(pos);
  const double t = pos - i;
  return i + 1 < v.size() ? v[i] * (1 - t) + v[i + 1] * t : v[i];
}

struct Stats {
  std::vector<double> errors;
  std::vector<double> errors2;  // second direction, where asked
  int none = 0;
  int none2 = 0;
  int total = 0;
};

void Header() {
  std::printf("%-46s %5s %8s %8s %8s %8s %8s %5s\n", "case", "n", "median", "p90", "p95", "p99",
              "max", "none");
}

void Row(const std::string& name, const std::vector<double>& e, int none) {
  std::printf("%-46s %5zu %8.3f %8.3f %8.3f %8.3f %8.3f %5d\n", name.c_str(), e.size(),
              Percentile(e, 0.5), Percentile(e, 0.9), Percentile(e, 0.95), Percentile(e, 0.99),
              Percentile(e, 1.0), none);
  std::fflush(stdout);
}

struct Case {
  double theta;
  double offset;
  double u, v, w;  // more uniform numbers for the shapes that need them
  uint64_t seed;
};

std::vector<Case> Cases(int n, uint64_t seed) {
  Pcg32 rng(seed);
  std::vector<Case> c(n);
  for (auto& x : c) {
    x.theta = 180.0 * rng.NextDouble();
    x.offset = -0.25 + 0.5 * rng.NextDouble();
    x.u = rng.NextDouble();
    x.v = rng.NextDouble();
    x.w = rng.NextDouble();
    x.seed = rng.NextU32();
  }
  return c;
}

// One estimate per case; `truth` gives the true direction(s) of a case (one
// or two); with two truths and o.second, the first estimate is scored
// against the first truth and the second against the second.
using Estimator = std::function<StatusOr<DirectionEstimate>(const Case&)>;

// One estimate per case by any estimator; `second`: score its second lobe.
Stats RunEstimator(const std::vector<Case>& cases, const Estimator& estimate, bool second,
                   const std::function<std::vector<double>(const Case&)>& truth, bool nearest = false) {
  Stats s;
  for (const Case& c : cases) {
    auto r = estimate(c);
    if (!r.ok()) {
      std::fprintf(stderr, "error: %s\n", r.status().message().c_str());
      std::exit(1);
    }
    ++s.total;
    const std::vector<double> t = truth(c);
    if (r->first.status != DirectionStatus::kFound) {
      ++s.none;
      s.errors.push_back(90.0);
    } else if (nearest && t.size() == 2) {
      // Either true direction may be the stronger one (a polygon corner):
      // score the first against the nearer, the second against the other.
      const double e0 = AngleError(r->first.theta_deg, t[0]);
      const double e1 = AngleError(r->first.theta_deg, t[1]);
      s.errors.push_back(std::min(e0, e1));
      if (second) {
        const double other = e0 <= e1 ? t[1] : t[0];
        if (r->second.status != DirectionStatus::kFound) {
          ++s.none2;
          s.errors2.push_back(90.0);
        } else {
          s.errors2.push_back(AngleError(r->second.theta_deg, other));
        }
      }
      continue;
    } else {
      s.errors.push_back(AngleError(r->first.theta_deg, t[0]));
    }
    if (second && t.size() == 2) {
      if (r->first.status != DirectionStatus::kFound || r->second.status != DirectionStatus::kFound) {
        ++s.none2;
        s.errors2.push_back(90.0);
      } else {
        s.errors2.push_back(AngleError(r->second.theta_deg, t[1]));
      }
    }
  }
  return s;
}

template <typename Make>
Stats Run(const std::vector<Case>& cases, const DirectionOptions& o, Make make,
          const std::function<std::vector<double>(const Case&)>& truth, bool nearest = false) {
  return RunEstimator(
      cases, [&](const Case& c) { return EstimateDirection(make(c), o); }, o.second, truth, nearest);
}

std::vector<double> Theta(const Case& c) { return {c.theta}; }

Integrand2 Step(const Case& c) {
  auto f = std::make_shared<StepIntegrand>(c.theta, c.offset);
  return [f](const Point2& p) { return (*f)(p); };
}

// Signed distance along the normal from the line through (1/2,1/2) + offset n.
double Distance(const Case& c, const Point2& p) {
  const Vec2 n = UnitVector(c.theta);
  return (p.x - 0.5) * n.x + (p.y - 0.5) * n.y - c.offset;
}

template <typename F>
double MedianSeconds(F f, int reps) {
  std::vector<double> t;
  for (int i = 0; i < reps; ++i) {
    const auto t0 = std::chrono::steady_clock::now();
    f();
    t.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  }
  return Percentile(t, 0.5);
}

}  // namespace

int main(int argc, char** argv) {
  int n = 500;
  bool timing = true;
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--cases") && i + 1 < argc) n = std::atoi(argv[++i]);
    if (!std::strcmp(argv[i], "--no-timing")) timing = false;
  }
  const auto cases = Cases(n, 12);
  const DirectionOptions def;
  auto grid = [](int w, int h, std::function<Integrand2(const Case&)> shape) {
    return [w, h, shape](const Case& c) { return PointSampledGrid(shape(c), w, h); };
  };

  std::printf("# direction_accuracy: %d cases per row, seed 12; errors in degrees (mod 180)\n", n);
  std::printf("# default: Tukey window 0.5, radii 2..7/16 W, weights P |v|^2 (samples: "
              "(P - 4 floor)+ |v|), line width 1, von Mises fit + line refinement\n\n");
  Header();
  // --- What it must show.
  const Stats clean = Run(cases, def, grid(64, 64, Step), Theta);
  Row("clean step 64x64", clean.errors, clean.none);
  {
    auto make = [](const Case& c) { return RandomSampledGrid(Step(c), 64, 64, 16, c.seed); };
    const Stats s = Run(cases, def, make, Theta);
    Row("noisy step 64x64, 16 random samples per cell", s.errors, s.none);
  }
  for (int m : {64, 256, 1024, 4096}) {
    auto make = [m](const Case& c) { return RandomSamples(Step(c), m, c.seed); };
    const Stats s = Run(cases, def, make, Theta);
    Row("scattered step, " + std::to_string(m) + " random samples", s.errors, s.none);
    std::vector<double> found;
    for (double e : s.errors) if (e < 90.0) found.push_back(e);
    Row("  same, only the cases with a direction", found, 0);
  }
  {
    // Two crossing edges: contrast 1 (theta) and 1/2 (theta2 = theta + 20..160),
    // offsets within +-0.15 so that both cross the patch.
    auto second = [](const Case& c) { return ReduceDirection(c.theta + 20.0 + 140.0 * c.u); };
    auto shape = [second](const Case& c) -> Integrand2 {
      auto a = std::make_shared<StepIntegrand>(c.theta, 0.6 * c.offset);
      auto b = std::make_shared<StepIntegrand>(second(c), -0.15 + 0.3 * c.v);
      return [a, b](const Point2& p) { return (*a)(p) + 0.5 * (*b)(p); };
    };
    DirectionOptions two = def;
    two.second = true;
    const Stats s = Run(cases, two, grid(64, 64, shape),
                        [second](const Case& c) { return std::vector<double>{c.theta, second(c)}; });
    Row("crossing edges 64x64 (contrast 1 : 0.5), theta1", s.errors, s.none);
    Row("crossing edges 64x64 (contrast 1 : 0.5), theta2", s.errors2, s.none2);
  }
  for (int px : {2, 8}) {
    const double width = px / 64.0;
    auto shape = [width](const Case& c) -> Integrand2 {
      return [c, width](const Point2& p) {
        const double t = std::clamp(Distance(c, p) / width + 0.5, 0.0, 1.0);
        return t * t * (3.0 - 2.0 * t);
      };
    };
    const Stats s = Run(cases, def, grid(64, 64, shape), Theta);
    Row("smoothed step 64x64, ramp " + std::to_string(px) + " px", s.errors, s.none);
  }
  for (int px : {2, 4}) {
    const double width = px / 64.0;
    auto shape = [width](const Case& c) -> Integrand2 {
      return [c, width](const Point2& p) { return std::fabs(Distance(c, p)) <= width / 2 ? 1.0 : 0.0; };
    };
    const Stats s = Run(cases, def, grid(64, 64, shape), Theta);
    Row("thin bar 64x64, " + std::to_string(px) + " px wide", s.errors, s.none);
  }
  {
    // A polygon corner: the wedge between two edges through a point c in the
    // middle of the patch, normals theta and theta + 30..120.
    auto other = [](const Case& c) { return ReduceDirection(c.theta + 30.0 + 90.0 * c.u); };
    auto shape = [other](const Case& c) -> Integrand2 {
      const Vec2 n1 = UnitVector(c.theta), n2 = UnitVector(other(c));
      const double cx = 0.35 + 0.3 * c.v, cy = 0.35 + 0.3 * c.w;
      return [=](const Point2& p) {
        const double a = (p.x - cx) * n1.x + (p.y - cy) * n1.y;
        const double b = (p.x - cx) * n2.x + (p.y - cy) * n2.y;
        return a >= 0.0 && b >= 0.0 ? 1.0 : 0.0;
      };
    };
    DirectionOptions two = def;
    two.second = true;
    const Stats s = Run(cases, two, grid(64, 64, shape),
                        [other](const Case& c) { return std::vector<double>{c.theta, other(c)}; },
                        /*nearest=*/true);
    Row("polygon corner 64x64, theta1 (nearer edge)", s.errors, s.none);
    Row("polygon corner 64x64, theta2 (other edge)", s.errors2, s.none2);
  }
  for (auto [w, h] : {std::pair{32, 32}, {128, 128}, {96, 48}, {8, 8}}) {
    const Stats s = Run(cases, def, grid(w, h, Step), Theta);
    Row("clean step " + std::to_string(w) + "x" + std::to_string(h), s.errors, s.none);
  }

  // --- No dominant direction: how many of each are flagged.
  std::printf("\n%-46s %8s\n", "no dominant direction (should be flagged)", "flagged");
  auto flagged = [&](const std::string& name, auto make) {
    int none = 0, total = 0;
    for (const Case& c : cases) {
      auto r = EstimateDirection(make(c), def);
      ++total;
      if (r.ok() && r->first.status != DirectionStatus::kFound) ++none;
    }
    std::printf("%-46s %4d/%-4d\n", name.c_str(), none, total);
    std::fflush(stdout);
  };
  flagged("constant grids (value 0.37 + 1000 u)", [](const Case& c) {
    return GridPatch{64, 64, std::vector<double>(64 * 64, 0.37 + 1000.0 * c.u)};
  });
  flagged("uniform white-noise grids 64x64", [](const Case& c) {
    Pcg32 rng(c.seed);
    GridPatch g{64, 64, std::vector<double>(64 * 64)};
    for (double& v : g.values) v = rng.NextDouble();
    return g;
  });
  flagged("disks 64x64 (centre 0.35..0.65, radius 0.1..0.35)", [](const Case& c) {
    const double cx = 0.35 + 0.3 * c.u, cy = 0.35 + 0.3 * c.v, r = 0.1 + 0.25 * c.w;
    return PointSampledGrid([=](const Point2& p) { return std::hypot(p.x - cx, p.y - cy) <= r ? 1.0 : 0.0; },
                            64, 64);
  });
  flagged("Gaussian blobs 64x64", [](const Case& c) {
    const double cx = 0.35 + 0.3 * c.u, cy = 0.35 + 0.3 * c.v, s = 0.05 + 0.15 * c.w;
    return PointSampledGrid(
        [=](const Point2& p) { return std::exp(-(std::pow(p.x - cx, 2) + std::pow(p.y - cy, 2)) / (2 * s * s)); },
        64, 64);
  });
  for (int m : {256, 1024, 4096}) {
    flagged("scattered white noise, " + std::to_string(m) + " samples", [m](const Case& c) {
      auto rng = std::make_shared<Pcg32>(c.seed + 1);
      return RandomSamples([rng](const Point2&) { return rng->NextDouble(); }, m, c.seed);
    });
    flagged("scattered disk, " + std::to_string(m) + " samples", [m](const Case& c) {
      const double cx = 0.35 + 0.3 * c.u, cy = 0.35 + 0.3 * c.v, r = 0.1 + 0.25 * c.w;
      return RandomSamples([=](const Point2& p) { return std::hypot(p.x - cx, p.y - cy) <= r ? 1.0 : 0.0; },
                           m, c.seed);
    });
  }

  // --- The edge-line fit (core/analysis/edge_line_fit.h) on scattered
  // samples: the same cases, random samples and the renderer's pre-pass
  // (Owen-scrambled Sobol, one scramble per case).
  std::printf("\nedge-line fit, scattered samples (core/analysis/edge_line_fit.h)\n");
  Header();
  auto owen = [](const Integrand2& f, int m, uint64_t seed) {
    SampledPatch s;
    s.points = OwenScrambledSobol(static_cast<uint32_t>(m), seed);
    for (const Point2& q : s.points) s.values.push_back(f(q));
    return s;
  };
  auto lines = [](auto make, bool second = false) -> Estimator {
    return [make, second](const Case& c) {
      EdgeLineOptions o;
      o.second = second;
      return EstimateEdgeLines(make(c), o);
    };
  };
  for (int m : {64, 256, 1024, 4096}) {
    for (bool sobol : {false, true}) {
      if (sobol && m == 4096) continue;
      auto make = [m, sobol, owen](const Case& c) {
        return sobol ? owen(Step(c), m, c.seed) : RandomSamples(Step(c), m, c.seed);
      };
      const Stats s = RunEstimator(cases, lines(make), false, Theta);
      Row("step, " + std::to_string(m) + (sobol ? " Owen-Sobol" : " random") + " samples", s.errors, s.none);
    }
    if (m == 4096) continue;
    // The renderer's nedgesM: the step continues across a 3 x 3 block of
    // pixels, each with its own M Owen-Sobol samples, read together.
    const Estimator pooled = [m, owen](const Case& c) {
      const Integrand2 step = Step(c);
      std::array<SampledPatch, 9> block;
      std::array<const SampledPatch*, 9> ptrs{};
      for (int k = 0; k < 9; ++k) {
        const double dx = k % 3 - 1, dy = k / 3 - 1;
        block[k] = owen([&](const Point2& p) { return step({p.x + dx, p.y + dy}); }, m, HashCombine(c.seed, k));
        ptrs[k] = &block[k];
      }
      return EstimateEdgeLinesPooled(ptrs, 0.5);
    };
    const Stats s = RunEstimator(cases, pooled, false, Theta);
    Row("step, " + std::to_string(m) + " Owen-Sobol a pixel, with neighbours", s.errors, s.none);
    // The same on a domain every pixel shares (the shadow's light): each
    // neighbour sees the step moved by 10-20% of the square, stacked.
    const Estimator stacked = [m, owen](const Case& c) {
      std::array<SampledPatch, 9> block;
      std::array<const SampledPatch*, 9> ptrs{};
      const double sx = 0.1 + 0.1 * c.v, sy = 0.1 + 0.1 * c.w;
      const Integrand2 step = Step(c);
      const Vec2 n = UnitVector(c.theta);
      for (int k = 0; k < 9; ++k) {
        const double dx = k % 3 - 1, dy = k / 3 - 1;
        const double moved = sx * dx - sy * dy;
        block[k] = owen([&](const Point2& p) { return step({p.x - moved * n.x, p.y - moved * n.y}); }, m,
                        HashCombine(c.seed, k));
        ptrs[k] = &block[k];
      }
      return EstimateEdgeLinesStacked(ptrs);
    };
    const Stats st = RunEstimator(cases, stacked, false, Theta);
    Row("step, " + std::to_string(m) + " Owen-Sobol a pixel, neighbours stacked", st.errors, st.none);
  }
  for (int m : {256, 1024}) {
    auto other = [](const Case& c) { return ReduceDirection(c.theta + 30.0 + 90.0 * c.u); };
    auto make = [m, other](const Case& c) {
      const Vec2 n1 = UnitVector(c.theta), n2 = UnitVector(other(c));
      const double cx = 0.35 + 0.3 * c.v, cy = 0.35 + 0.3 * c.w;
      return RandomSamples(
          [=](const Point2& p) {
            const double a = (p.x - cx) * n1.x + (p.y - cy) * n1.y;
            const double b = (p.x - cx) * n2.x + (p.y - cy) * n2.y;
            return a >= 0.0 && b >= 0.0 ? 1.0 : 0.0;
          },
          m, c.seed);
    };
    const Stats s = RunEstimator(cases, lines(make, true), true,
                                 [other](const Case& c) { return std::vector<double>{c.theta, other(c)}; },
                                 /*nearest=*/true);
    Row("polygon corner, " + std::to_string(m) + " random, theta1", s.errors, s.none);
    Row("polygon corner, " + std::to_string(m) + " random, theta2", s.errors2, s.none2);
  }
  for (int m : {256, 1024}) {
    auto make = [m](const Case& c) {
      return RandomSamples(
          [c](const Point2& p) {
            const double t = std::clamp(Distance(c, p) / (8.0 / 64.0) + 0.5, 0.0, 1.0);
            return t * t * (3.0 - 2.0 * t);
          },
          m, c.seed);
    };
    const Stats s = RunEstimator(cases, lines(make), false, Theta);
    Row("smoothed step (ramp 1/8), " + std::to_string(m) + " random", s.errors, s.none);
    auto bar = [m](const Case& c) {
      return RandomSamples([c](const Point2& p) { return std::fabs(Distance(c, p)) <= 1.0 / 64 ? 1.0 : 0.0; },
                           m, c.seed);
    };
    const Stats b = RunEstimator(cases, lines(bar), false, Theta);
    Row("thin bar (1/32 wide), " + std::to_string(m) + " random", b.errors, b.none);
    auto shaded = [m](const Case& c) {
      // A step of contrast 1 on a linear gradient of range 1 across the pixel.
      return RandomSamples([c](const Point2& p) { return (Distance(c, p) >= 0 ? 1.0 : 0.0) + p.x * c.u + p.y * (1 - c.u); },
                           m, c.seed);
    };
    const Stats sh = RunEstimator(cases, lines(shaded), false, Theta);
    Row("step on a gradient of equal range, " + std::to_string(m) + " random", sh.errors, sh.none);
  }
  std::printf("\n%-46s %8s\n", "edge-line fit: no edge (should be flagged)", "flagged");
  auto flagged_lines = [&](const std::string& name, auto make) {
    int none = 0, total = 0;
    for (const Case& c : cases) {
      auto r = EstimateEdgeLines(make(c));
      ++total;
      if (r.ok() && r->first.status != DirectionStatus::kFound) ++none;
    }
    std::printf("%-46s %4d/%-4d\n", name.c_str(), none, total);
    std::fflush(stdout);
  };
  for (int m : {64, 256, 1024}) {
    const std::string at = ", " + std::to_string(m) + " samples";
    flagged_lines("white noise" + at, [m](const Case& c) {
      auto rng = std::make_shared<Pcg32>(c.seed + 1);
      return RandomSamples([rng](const Point2&) { return rng->NextDouble(); }, m, c.seed);
    });
    flagged_lines("disk (radius 0.1..0.35)" + at, [m](const Case& c) {
      const double cx = 0.35 + 0.3 * c.u, cy = 0.35 + 0.3 * c.v, r = 0.1 + 0.25 * c.w;
      return RandomSamples([=](const Point2& p) { return std::hypot(p.x - cx, p.y - cy) <= r ? 1.0 : 0.0; },
                           m, c.seed);
    });
    flagged_lines("Gaussian blob (sigma 0.05..0.2)" + at, [m](const Case& c) {
      const double cx = 0.35 + 0.3 * c.u, cy = 0.35 + 0.3 * c.v, s = 0.05 + 0.15 * c.w;
      return RandomSamples(
          [=](const Point2& p) { return std::exp(-(std::pow(p.x - cx, 2) + std::pow(p.y - cy, 2)) / (2 * s * s)); },
          m, c.seed);
    });
    flagged_lines("linear gradient" + at, [m](const Case& c) {
      return RandomSamples([c](const Point2& p) { return p.x * std::cos(c.theta) + p.y * std::sin(c.theta); }, m,
                           c.seed);
    });
  }

  // --- Choices (docs/method.md, "Where alignset chooses"): the same clean 64x64 steps.
  std::printf("\nchoices, clean step 64x64\n");
  Header();
  auto choice = [&](const std::string& name, DirectionOptions o) {
    const Stats s = Run(cases, o, grid(64, 64, Step), Theta);
    Row(name, s.errors, s.none);
  };
  choice("default (Tukey 0.5, fit + refine)", def);
  { DirectionOptions o = def; o.refine = false; choice("fit only (no refinement)", o); }
  { DirectionOptions o = def; o.starts = 1; choice("one start (argmax) instead of 3", o); }
  { DirectionOptions o = def; o.spectrum.window_taper = 1.0; choice("Hann window", o); }
  { DirectionOptions o = def; o.spectrum.window_taper = 0.2; choice("Tukey 0.2", o); }
  { DirectionOptions o = def; o.spectrum.window_taper = 0.0; choice("no window", o); }
  for (double ex : {2.0, 5.0}) {
    DirectionOptions o = def;
    o.spectrum.window_taper = 0.0;
    o.axis_exclusion_deg = ex;
    char name[80];
    std::snprintf(name, sizeof name, "no window, axes +-%.0f deg left out", ex);
    choice(name, o);
  }
  { DirectionOptions o = def; o.axis_exclusion_deg = 2.0; choice("Tukey 0.5 and axes +-2 deg left out", o); }
  for (double b : {0.0, 1.0, 3.0}) {
    DirectionOptions o = def;
    o.radial_power = b;
    choice("radial weight |v|^" + std::to_string(static_cast<int>(b)), o);
  }
  for (double sg : {0.5, 2.0}) {
    DirectionOptions o = def;
    o.sigma = sg;
    choice(sg < 1 ? "line width 0.5" : "line width 2", o);
  }
  { DirectionOptions o = def; o.spectrum.max_radius = 20; choice("max radius 20 (default 28)", o); }
  {
    std::printf("\nchoices, scattered step, 1024 samples\n");
    Header();
    for (double b : {1.0, 2.0}) {
      for (double t : {1.0, 4.0}) {
        DirectionOptions o = def;
        o.radial_power = b;
        o.noise_threshold = t;
        auto make = [](const Case& c) { return RandomSamples(Step(c), 1024, c.seed); };
        const Stats s = Run(cases, o, make, Theta);
        char name[80];
        std::snprintf(name, sizeof name, "weights (P - %.0f floor)+ |v|^%.0f", t, b);
        Row(name, s.errors, s.none);
      }
    }
  }

  if (timing) {
    // --- Cost: medians of repeated runs, one thread.
    std::printf("\ncost (median of repeated runs, one thread)\n");
    Case c = cases[0];
    for (int side : {64, 256, 1024}) {
      const GridPatch g = PointSampledGrid(Step(c), side, side);
      const double t = MedianSeconds([&] { (void)EstimateDirection(g, def); }, side >= 1024 ? 5 : 21);
      const double ts = MedianSeconds([&] { (void)GridPowerSpectrum(g, def.spectrum); }, 21);
      std::printf("grid %4dx%-4d  estimate %8.2f ms   of which FFT spectrum %7.3f ms\n", side, side,
                  1e3 * t, 1e3 * ts);
    }
    {
      const GridPatch g = PointSampledGrid(Step(c), 64, 64);
      DirectEngine direct(1);
      FastEngine fast(1);
      const double td = MedianSeconds([&] { (void)GridPowerSpectrumByEngine(g, def.spectrum, &direct); }, 11);
      const double tf = MedianSeconds([&] { (void)GridPowerSpectrumByEngine(g, def.spectrum, &fast); }, 11);
      std::printf("grid   64x64   spectrum at the cell centres: direct engine %7.3f ms, fast engine %7.3f ms\n",
                  1e3 * td, 1e3 * tf);
    }
    for (int m : {256, 1024, 65536, 1 << 20}) {
      const SampledPatch s = RandomSamples(Step(c), m, 1);
      const double t = MedianSeconds([&] { (void)EstimateDirection(s, def); }, m >= (1 << 20) ? 3 : 11);
      std::printf("samples %8d  estimate %8.2f ms\n", m, 1e3 * t);
    }
    for (int m : {64, 256, 1024, 4096}) {
      const SampledPatch s = RandomSamples(Step(c), m, 1);
      const double t = MedianSeconds([&] { (void)EstimateEdgeLines(s); }, 21);
      std::printf("samples %8d  edge-line fit %8.3f ms\n", m, 1e3 * t);
    }
  }
  return 0;
}

// What the estimate costs in variance (issue 12, "Misalignment table"): for
// step edges at random angles, the set served for the estimated direction
// against the set for the true direction, on the same edges.
//   build/bench/direction_misalignment [--cases 12] [--n 1024,4096] [--threads 2]
//     > bench/results/direction_misalignment.txt
// Sets are optimized in-process with the optimizer's current defaults
// (OptimizerOptions{}, DefaultFrequencyParams, seed 1, fast engine), so the
// table can be re-run whenever those defaults change. A served set is the
// canonical set of the served key aligned by its group element, exactly as
// the service does it; the reference is a set optimized for the true,
// unrounded angle. Variance: StepEdgeVariance with the true normal (8
// parallel edges at offsets -1/4..1/4, 4096 Cranley-Patterson shifts, the
// same shifts for every set).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "core/align/canonical.h"
#include "core/analysis/direction_estimate.h"
#include "core/analysis/patch_sampling.h"
#include "core/analysis/step_integrand.h"
#include "core/analysis/variance.h"
#include "core/optimize/optimizer.h"
#include "core/spectral/spectral_engine.h"
#include "core/util/angles.h"
#include "core/util/hash.h"

using namespace alignset;

namespace {

double AngleError(double a, double b) {
  double d = std::fmod(std::fabs(a - b), 180.0);
  return std::min(d, 180.0 - d);
}

class SetMaker {
 public:
  SetMaker(uint32_t n, int threads) : n_(n) {
    auto e = MakeSpectralEngine(EngineKind::kFast, threads);
    if (!e.ok()) {
      std::fprintf(stderr, "%s\n", e.status().message().c_str());
      std::exit(1);
    }
    engine_ = std::move(e).value();
  }
  // The set optimized for exactly `deg` (memoised).
  const PointSet& For(double deg) {
    auto it = sets_.find(deg);
    if (it != sets_.end()) return it->second;
    OptimizationProblem p;
    p.n = n_;
    p.directions = {deg};
    p.seed = 1;
    auto r = Optimize(p, OptimizerOptions{}, *engine_);
    if (!r.ok()) {
      std::fprintf(stderr, "optimize %g: %s\n", deg, r.status().message().c_str());
      std::exit(1);
    }
    return sets_.emplace(deg, std::move(r->points)).first->second;
  }
  // The set the service serves for `deg` on `grid`.
  PointSet Served(double deg, AngleGrid grid, double* served) {
    auto c = Canonicalize({deg}, grid);
    *served = c->served_exact_deg[0];
    return Align(For(Phi1Degrees(c->key)), c->ops);
  }

 private:
  uint32_t n_;
  std::unique_ptr<SpectralEngine> engine_;
  std::map<double, PointSet> sets_;
};

struct Row {
  std::vector<double> ratio;   // variance / variance of the true-angle set
  std::vector<double> offset;  // |served - true|
};

void Print(const char* name, const Row& r) {
  std::vector<double> v = r.ratio;
  std::sort(v.begin(), v.end());
  double mean = 0, off = 0;
  for (double x : v) mean += x / v.size();
  for (double x : r.offset) off += x / r.offset.size();
  std::printf("  %-44s mean |served - true| %6.3f deg   variance / true-angle set: mean %6.3f  "
              "median %6.3f  max %6.3f\n",
              name, off, mean, v[v.size() / 2], v.back());
  std::fflush(stdout);
}

}  // namespace

int main(int argc, char** argv) {
  int cases = 12, threads = 2;
  std::vector<uint32_t> ns = {1024, 4096};
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--cases") && i + 1 < argc) cases = std::atoi(argv[++i]);
    if (!std::strcmp(argv[i], "--threads") && i + 1 < argc) threads = std::atoi(argv[++i]);
    if (!std::strcmp(argv[i], "--n") && i + 1 < argc) {
      ns.clear();
      for (char* t = std::strtok(argv[++i], ","); t; t = std::strtok(nullptr, ",")) ns.push_back(std::atoi(t));
    }
  }
  // The edges and their estimates (independent of N).
  struct Case {
    double theta, offset, est_grid, est_samples;
  };
  std::vector<Case> cs;
  Pcg32 rng(2024);
  for (int i = 0; i < cases; ++i) {
    Case c;
    c.theta = 180.0 * rng.NextDouble();
    c.offset = -0.2 + 0.4 * rng.NextDouble();
    const StepIntegrand f(c.theta, c.offset);
    auto fn = [&](const Point2& p) { return f(p); };
    auto g = EstimateDirection(PointSampledGrid(fn, 64, 64));
    auto s = EstimateDirection(RandomSamples(fn, 1024, rng.NextU32()));
    if (!g.ok() || !s.ok() || g->first.status != DirectionStatus::kFound) {
      std::fprintf(stderr, "case %d: no estimate\n", i);
      return 1;
    }
    c.est_grid = g->first.theta_deg;
    // A scattered estimate that finds nothing is served as the grid would be
    // served at 0 deg: the caller would fall back to an axis-only set.
    c.est_samples = s->first.status == DirectionStatus::kFound ? s->first.theta_deg : 0.0;
    cs.push_back(c);
  }
  std::printf("# direction_misalignment: %d edges (random normal, offset -0.2..0.2); estimates from a "
              "64x64 point-sampled patch and from 1024 random samples\n",
              cases);
  for (const Case& c : cs) {
    std::printf("#   true %8.3f  grid estimate %8.3f (err %.3f)  1024-sample estimate %8.3f (err %.3f)\n",
                c.theta, c.est_grid, AngleError(c.est_grid, c.theta), c.est_samples,
                AngleError(c.est_samples, c.theta));
  }
  for (uint32_t n : ns) {
    SetMaker maker(n, threads);
    Row true_q, true_1, grid_q, grid_1, samp_q, samp_1;
    double mean_true = 0;
    for (size_t i = 0; i < cs.size(); ++i) {
      const Case& c = cs[i];
      const uint64_t seed = 100 + i;
      auto var = [&](const PointSet& p) {
        return StepEdgeVariance(p, c.theta, 8, 4096, seed).variance;
      };
      const double ref = var(maker.For(c.theta));
      mean_true += ref / cs.size();
      auto add = [&](Row* row, double deg, AngleGrid grid) {
        double served = 0;
        const PointSet p = maker.Served(deg, grid, &served);
        row->ratio.push_back(var(p) / ref);
        row->offset.push_back(AngleError(served, c.theta));
      };
      add(&true_q, c.theta, AngleGrid::kQuarterDegree);
      add(&true_1, c.theta, AngleGrid::kWholeDegree);
      add(&grid_q, c.est_grid, AngleGrid::kQuarterDegree);
      add(&grid_1, c.est_grid, AngleGrid::kWholeDegree);
      add(&samp_q, c.est_samples, AngleGrid::kQuarterDegree);
      add(&samp_1, c.est_samples, AngleGrid::kWholeDegree);
    }
    std::printf("\nN = %u (mean variance of the true-angle sets %.3e)\n", n, mean_true);
    Print("true angle, quarter-degree grid", true_q);
    Print("true angle, 1-degree grid", true_1);
    Print("64x64 patch estimate, quarter-degree grid", grid_q);
    Print("64x64 patch estimate, 1-degree grid", grid_1);
    Print("1024-sample estimate, quarter-degree grid", samp_q);
    Print("1024-sample estimate, 1-degree grid", samp_1);
  }
  return 0;
}

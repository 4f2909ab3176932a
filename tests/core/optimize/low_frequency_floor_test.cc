// The acceptance of the low-frequency floor at N = 256, where it runs in
// seconds: the default set for θ = 30° beats Owen-scrambled Sobol (the mean
// of 16 scrambles, on the same integrands and the same CP shifts) on the
// Gaussian and on both axis edges, and is at least 2.5x better on its own
// edge. The supplement's flat-loss profile fails the Gaussian part, which is
// what the levers are for (bench/integrand_family has every N and angle).
#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <vector>

#include "core/analysis/integrands.h"
#include "core/analysis/variance.h"
#include "core/optimize/optimizer.h"
#include "core/sampling/owen_sobol.h"
#include "core/spectral/fast_engine.h"

namespace alignset {
namespace {

constexpr uint32_t kN = 256;
constexpr double kTheta = 30.0;
constexpr int kShifts = 1024;
constexpr int kScrambles = 16;

// A step edge is averaged over 8 parallel positions, as in
// bench/integrand_family, so the figure belongs to the set and not to one
// lucky edge position.
struct Family {
  std::vector<std::unique_ptr<Integrand>> step_theta, step_0, step_90, gaussian;
};

Family MakeFamily() {
  Family f;
  for (int e = 0; e < 8; ++e) {
    const double offset = 0.5 * (e + 0.5) / 8 - 0.25;
    f.step_theta.push_back(StepEdge(kTheta, offset));
    f.step_0.push_back(StepEdge(0.0, offset));
    f.step_90.push_back(StepEdge(90.0, offset));
  }
  f.gaussian.push_back(std::move(MakeIntegrand("gaussian")).value());
  return f;
}

double Variance(const PointSet& p, const std::vector<std::unique_ptr<Integrand>>& parts) {
  double v = 0.0;
  for (const auto& f : parts) {
    const Integrand& g = *f;
    v += CranleyPattersonVariance(
             p, [&](const Point2& q) { return g.Value(q); }, g.Integral(), kShifts, 777)
             .variance;
  }
  return v / static_cast<double>(parts.size());
}

struct Figures {
  double step_theta = 0, step_0 = 0, step_90 = 0, gaussian = 0;
};

Figures Measure(const PointSet& p, const Family& f) {
  return {Variance(p, f.step_theta), Variance(p, f.step_0), Variance(p, f.step_90),
          Variance(p, f.gaussian)};
}

Figures OwenSobol(const Family& f) {
  Figures mean;
  for (int s = 0; s < kScrambles; ++s) {
    const Figures one = Measure(OwenScrambledSobol(kN, 1000 + s), f);
    mean.step_theta += one.step_theta / kScrambles;
    mean.step_0 += one.step_0 / kScrambles;
    mean.step_90 += one.step_90 / kScrambles;
    mean.gaussian += one.gaussian / kScrambles;
  }
  return mean;
}

PointSet OptimizedSet(const OptimizerOptions& options, const FrequencyParams& params) {
  OptimizationProblem problem;
  problem.n = kN;
  problem.directions = {kTheta};
  problem.seed = 1;
  problem.frequency_params = params;
  FastEngine engine(2);
  auto r = Optimize(problem, options, engine);
  EXPECT_TRUE(r.ok()) << r.status().ToString();
  return r.ok() ? r->points : PointSet{};
}

TEST(LowFrequencyFloor, DefaultSetBeatsOwenSobolOnTheGaussianAndBothAxisEdges) {
  const Family family = MakeFamily();
  const Figures owen = OwenSobol(family);
  const Figures ours = Measure(OptimizedSet(OptimizerOptions{}, DefaultFrequencyParams(kN)), family);
  EXPECT_LT(ours.gaussian, owen.gaussian) << ours.gaussian << " vs " << owen.gaussian;
  EXPECT_LT(ours.step_0, owen.step_0) << ours.step_0 << " vs " << owen.step_0;
  EXPECT_LT(ours.step_90, owen.step_90) << ours.step_90 << " vs " << owen.step_90;
  EXPECT_LT(2.5 * ours.step_theta, owen.step_theta) << ours.step_theta << " vs " << owen.step_theta;

  // The supplement's profile keeps the floor: many times Owen-Sobol's
  // variance on the Gaussian.
  const Figures flat = Measure(
      OptimizedSet(SupplementOptimizerOptions(), SupplementFrequencyParams(kN)), family);
  EXPECT_GT(flat.gaussian, 2.0 * owen.gaussian) << flat.gaussian << " vs " << owen.gaussian;
  std::printf("N=%u theta=%g, ratio to Owen-Sobol (16 scrambles): step theta %.3f, step 0 %.3f, "
              "step 90 %.3f, gaussian %.4f; supplement profile: gaussian %.2f\n",
              kN, kTheta, ours.step_theta / owen.step_theta, ours.step_0 / owen.step_0,
              ours.step_90 / owen.step_90, ours.gaussian / owen.gaussian,
              flat.gaussian / owen.gaussian);
}

}  // namespace
}  // namespace alignset

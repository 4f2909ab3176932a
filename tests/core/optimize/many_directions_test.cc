// The optimizer with 3 to 8 arbitrary directions (issue 14).
#include <gtest/gtest.h>

#include <vector>

#include "core/optimize/optimizer.h"
#include "core/spectral/direct_engine.h"
#include "core/spectral/scaled_loss_engine.h"

namespace alignset {
namespace {

OptimizationProblem Problem(std::vector<double> dirs) {
  OptimizationProblem p;
  p.n = 64;
  p.directions = std::move(dirs);
  p.seed = 3;
  return p;
}

TEST(ManyDirections, ValidationTakesOneToEightDistinctDirections) {
  EXPECT_TRUE(ValidateProblem(Problem({10, 40, 70, 100, 130, 150, 160, 170})).ok());
  const Status nine = ValidateProblem(Problem({1, 2, 3, 4, 5, 6, 7, 8, 9}));
  EXPECT_EQ(nine.code(), Status::Code::kInvalidArgument);
  EXPECT_NE(nine.message().find("1 to 8"), std::string::npos) << nine.message();
  const Status twice = ValidateProblem(Problem({30, 50, 210}));
  EXPECT_EQ(twice.code(), Status::Code::kInvalidArgument);
  EXPECT_NE(twice.message().find("duplicate direction 30"), std::string::npos) << twice.message();
  const Status axis = ValidateProblem(Problem({30, 50, 180}));
  EXPECT_NE(axis.message().find("0 and 90 are always included"), std::string::npos)
      << axis.message();
  // The service's space keeps its repeated pairs and its axis keys.
  EXPECT_TRUE(ValidateProblem(Problem({30, 30})).ok());
  EXPECT_TRUE(ValidateProblem(Problem({0})).ok());
}

TEST(ManyDirections, FiveDirectionsUseTheSharedBudgetAndLowerTheLoss) {
  DirectEngine engine(1);
  OptimizerOptions options;
  options.max_iterations = 60;
  auto r = Optimize(Problem({20, 50, 110}), options, engine);
  ASSERT_TRUE(r.ok()) << r.status().message();
  EXPECT_EQ(r->frequency_params, FrequencyParamsForDirections(64, 3));
  EXPECT_NE(r->frequency_params, DefaultFrequencyParams(64));
  EXPECT_LT(r->final_loss.spectrum, 0.5 * r->initial.spectrum);
  // Every strip of the five directions is darker than white noise.
  const std::vector<double> dirs = {0, 90, 20, 50, 110};
  engine.SetFrequencies(BuildFrequencySet(r->frequency_params, dirs));
  for (double d : dirs) {
    engine.SetFrequencies(StripFrequencies(r->frequency_params, d));
    SpectrumEvaluation e;
    engine.Evaluate(r->points, false, &e);
    EXPECT_LT(e.loss, 0.5) << d;
  }
}

TEST(ManyDirections, AZeroScaledSpectrumLossLeavesTheSlicedWassersteinTermAlone) {
  DirectEngine inner(1);
  ScaledLossEngine engine(inner, 0.0);
  OptimizerOptions options;
  options.max_iterations = 40;
  options.divergence_signal = DivergenceSignal::kTotalLoss;
  auto r = Optimize(Problem({30}), options, engine);
  ASSERT_TRUE(r.ok());
  EXPECT_EQ(r->final_loss.spectrum, 0.0);
  EXPECT_LT(r->final_loss.sw, r->initial.sw);
  // Scale 1 is the inner engine itself, bit for bit.
  DirectEngine a(1), b(1);
  ScaledLossEngine same(b, 1.0);
  auto ra = Optimize(Problem({30}), options, a);
  auto rb = Optimize(Problem({30}), options, same);
  ASSERT_TRUE(ra.ok() && rb.ok());
  EXPECT_EQ(ra->points, rb->points);
}

}  // namespace
}  // namespace alignset

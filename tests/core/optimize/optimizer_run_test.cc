#include <gtest/gtest.h>

#include "core/optimize/optimizer.h"
#include "core/spectral/direct_engine.h"
#include "core/spectral/fast_engine.h"

namespace alignset {
namespace {

OptimizationProblem Problem(uint32_t n, std::vector<double> dirs) {
  OptimizationProblem p;
  p.n = n;
  p.directions = std::move(dirs);
  p.seed = 3;
  return p;
}

OptimizerOptions Options(int iterations) {
  OptimizerOptions o;
  o.max_iterations = iterations;
  o.progress_every = 1;
  o.stall_iterations = 25;  // so that the plateau rule fires inside the run
  return o;
}

// Runs `problem` in slices of `slice` iterations, alternating between two
// engines and running another problem on the engine in between, so that every
// resume has to set its frequencies again.
OptimizationResult Sliced(const OptimizationProblem& problem, const OptimizerOptions& o, int slice,
                          SpectralEngine& a, SpectralEngine& b, int* slices) {
  auto run = OptimizerRun::Create(problem, o);
  EXPECT_TRUE(run.ok());
  int count = 0;
  *slices = 0;
  OptimizerRun::Outcome out = OptimizerRun::Outcome::kPaused;
  while (out == OptimizerRun::Outcome::kPaused) {
    SpectralEngine& engine = (*slices % 2 == 0) ? a : b;
    out = (*run)->Resume(engine, false, [&](const ProgressInfo&) {
      return ++count % slice == 0 ? RunControl::kPause : RunControl::kContinue;
    });
    ++*slices;
    // Something else runs on the engine between two slices.
    auto other = Optimize(Problem(problem.n, {problem.directions[0] + 17.0}), Options(3), engine);
    EXPECT_TRUE(other.ok());
  }
  EXPECT_EQ(out, OptimizerRun::Outcome::kFinished);
  return (*run)->TakeResult();
}

void ExpectSameRun(const OptimizationResult& x, const OptimizationResult& y) {
  EXPECT_EQ(x.points, y.points);  // bit for bit
  EXPECT_EQ(x.iterations, y.iterations);
  EXPECT_EQ(x.reverts, y.reverts);
  EXPECT_EQ(x.final_loss.total, y.final_loss.total);
  EXPECT_EQ(x.final_learning_rate, y.final_learning_rate);
  EXPECT_EQ(x.stop_reason, y.stop_reason);
}

TEST(OptimizerRun, PausedAndResumedOnOtherEnginesGivesTheSameBits) {
  DirectEngine reference_engine(1), a(2), b(1);
  const auto problem = Problem(128, {30.0});
  const auto o = Options(150);
  auto whole = Optimize(problem, o, reference_engine);
  ASSERT_TRUE(whole.ok());
  int slices = 0;
  ExpectSameRun(Sliced(problem, o, 7, a, b, &slices), *whole);
  EXPECT_GE(slices, 150 / 7);
}

TEST(OptimizerRun, FastEngineTwoDirectionsAlsoResumeExactly) {
  FastEngine reference_engine(1), a(2), b(1);
  const auto problem = Problem(512, {20.0, 110.0});
  const auto o = Options(120);
  auto whole = Optimize(problem, o, reference_engine);
  ASSERT_TRUE(whole.ok());
  int slices = 0;
  ExpectSameRun(Sliced(problem, o, 11, a, b, &slices), *whole);
  EXPECT_GT(slices, 5);
}

// The optional levers add state across slices: the phase and its loss
// weights (set again on a rebound engine), the axis clamp's orders, the
// start set, the final projection.
TEST(OptimizerRun, WarmupPhaseAxisClampAndProjectionAlsoResumeExactly) {
  FastEngine reference_engine(1), a(2), b(1);
  auto problem = Problem(256, {20.0, 100.0});
  // Table 1's K: with it this run reaches its budget before the plateau rule
  // stops it, so every phase is crossed by slices.
  problem.frequency_params = SupplementFrequencyParams(256);
  {  // continue from a briefly optimized set
    auto first = Optimize(problem, Options(20), reference_engine);
    ASSERT_TRUE(first.ok());
    problem.start = first->points;
    problem.seed = 99;  // unused with a start set
  }
  auto o = Options(120);
  o.warmup_fraction = 0.3;
  o.warmup_weighting.exponent = 1.0;
  o.weighting.exponent = 0.5;
  o.stratify_axes = true;
  o.zero_radius = 2.0;
  o.final_margin = 0.1;
  auto whole = Optimize(problem, o, reference_engine);
  ASSERT_TRUE(whole.ok());
  int slices = 0;
  ExpectSameRun(Sliced(problem, o, 13, a, b, &slices), *whole);
  EXPECT_EQ(whole->iterations, 120);
  EXPECT_GE(slices, 120 / 13);
}

TEST(OptimizerRun, CancelKeepsTheBestSetSoFarAndHoldsNoMoreThanTheState) {
  DirectEngine engine(1);
  auto small = Problem(64, {10.0});
  small.frequency_params = SupplementFrequencyParams(64);  // |K| as the bound assumes
  auto run = OptimizerRun::Create(small, Options(100));
  ASSERT_TRUE(run.ok());
  EXPECT_EQ((*run)->Resume(engine, false, [](const ProgressInfo& p) {
    return p.iteration == 10 ? RunControl::kPause : RunControl::kContinue;
  }), OptimizerRun::Outcome::kPaused);
  EXPECT_EQ((*run)->iteration(), 10);
  // Paused: the Adam state (x, m, v, gradient) and the best set, about 80
  // bytes a point, plus K and the SW tables; the trial state is dropped.
  // With the default levers, also the clamp's two orders and the weights
  // of the two phases.
  EXPECT_LT((*run)->HeldBytes(), 64u * 80 + 64u * 4 * 12 + 200 * sizeof(Frequency) +
                                     2 * 64u * sizeof(uint32_t) + 2 * 200 * sizeof(double));
  EXPECT_EQ((*run)->Resume(engine, true, [](const ProgressInfo& p) {
    return p.iteration == 20 ? RunControl::kCancel : RunControl::kContinue;
  }), OptimizerRun::Outcome::kCancelled);
  const OptimizationResult r = (*run)->TakeResult();
  EXPECT_EQ(r.iterations, 20);
  EXPECT_EQ(r.stop_reason, StopReason::kCancelled);
  EXPECT_EQ(r.points.size(), 64u);
  EXPECT_LE(r.final_loss.total, r.initial.total);
}

}  // namespace
}  // namespace alignset

#include "core/spectral/fast_engine.h"

#include <gtest/gtest.h>

#include "tests/core/spectral/relative_error.h"

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "core/spectral/direct_engine.h"
#include "core/spectral/frequency_set.h"
#include "core/optimize/optimizer.h"
#include "core/sampling/owen_sobol.h"

namespace alignset {
namespace {

using test_support::RelativeError;

PointSet WhiteNoise(size_t n, uint32_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  PointSet p(n);
  for (Point2& s : p) s = {u(rng), u(rng)};
  return p;
}

struct Comparison {
  double spectrum_error;
  double gradient_error;
  double loss_error;
};

Comparison Compare(const std::vector<Frequency>& k, const PointSet& points,
                   double tolerance = FastEngine::kDefaultTolerance) {
  DirectEngine direct(2);
  FastEngine fast(2, tolerance);
  direct.SetFrequencies(k);
  fast.SetFrequencies(k);
  SpectrumEvaluation want, got;
  direct.Evaluate(points, true, &want);
  fast.Evaluate(points, true, &got);
  EXPECT_EQ(got.spectrum.size(), k.size());
  EXPECT_EQ(got.gradient.size(), points.size());
  return {RelativeError(got.spectrum, want.spectrum), RelativeError(got.gradient, want.gradient),
          std::abs(got.loss - want.loss) / want.loss};
}

constexpr double kRequired = 1e-6;

struct Case {
  uint32_t n;
  std::vector<double> directions;
};

std::string CaseName(const testing::TestParamInfo<Case>& info) {
  std::string s = "N";
  s += std::to_string(info.param.n);
  for (double d : info.param.directions) {
    const int tenths = static_cast<int>(std::round(d * 10));
    s += tenths < 0 ? "_m" : "_";
    s += std::to_string(std::abs(tenths));
  }
  return s;
}

class FastMatchesDirect : public testing::TestWithParam<Case> {};

TEST_P(FastMatchesDirect, OnOwenSobolAndWhiteNoise) {
  const Case& c = GetParam();
  const std::vector<Frequency> k =
      BuildFrequencySet(DefaultFrequencyParams(c.n), AnisotropyDirections(c.directions));
  for (const PointSet& points : {OwenScrambledSobol(c.n, 11), WhiteNoise(c.n, c.n)}) {
    const Comparison r = Compare(k, points);
    EXPECT_LT(r.spectrum_error, kRequired);
    EXPECT_LT(r.gradient_error, kRequired);
    EXPECT_LT(r.loss_error, kRequired);
  }
}

// Directions in every quadrant (spectral convention, mod 180), near the axes
// and the diagonal, and 4-direction sets (two arbitrary directions),
// including two close directions whose strips merge into one piece.
INSTANTIATE_TEST_SUITE_P(
    Sets, FastMatchesDirect,
    testing::Values(Case{16, {30}}, Case{64, {30}}, Case{64, {120, 45}}, Case{300, {30}},
                    Case{300, {100}}, Case{300, {165.5}}, Case{300, {20, 110}},
                    Case{1024, {30}}, Case{1024, {135}}, Case{1024, {1}}, Case{1024, {89.3}},
                    Case{1024, {60, 61}}, Case{1024, {10, 170}}, Case{1500, {75}},
                    Case{4096, {30}}, Case{4096, {150, 40}}, Case{4096, {-17}}),
    CaseName);

TEST(FastEngineTest, MatchesDirectOnAnOptimizedSet) {
  // Inside K the spectrum of an optimized set is small, so the fast
  // engine's absolute error is measured against much smaller values (and
  // the gradient is a small sum of large terms).
  OptimizationProblem problem;
  problem.n = 256;
  problem.directions = {30.0};
  problem.seed = 5;
  problem.frequency_params = SupplementFrequencyParams(256);
  OptimizerOptions options = SupplementOptimizerOptions();
  options.max_iterations = 600;
  DirectEngine engine(2);
  auto result = Optimize(problem, options, engine);
  ASSERT_TRUE(result.ok()) << result.status().ToString();
  ASSERT_LT(result->final_loss.spectrum, 0.01 * result->initial.spectrum);

  const std::vector<Frequency> k =
      BuildFrequencySet(DefaultFrequencyParams(problem.n), AnisotropyDirections({30.0}));
  const Comparison r = Compare(k, result->points);
  EXPECT_LT(r.spectrum_error, kRequired);
  EXPECT_LT(r.gradient_error, kRequired);
  EXPECT_LT(r.loss_error, kRequired);
}

TEST(FastEngineTest, MatchesDirectOnArbitraryFrequencySets) {
  // K without any strip structure, with DC, both signs of a frequency and
  // duplicates: the partition must still cover every entry once. (b >= 0:
  // the direct engine's tables start at b = 0.)
  std::mt19937 rng(3);
  std::uniform_int_distribution<int> coord(-150, 150);
  std::uniform_int_distribution<int> row(0, 150);
  std::vector<Frequency> k = {{0, 0}, {1, 0}, {-1, 0}, {3, 4}, {3, 4}, {-7, 0}};
  for (int i = 0; i < 400; ++i) k.push_back({coord(rng), row(rng)});
  for (int i = 0; i < 200; ++i) k.push_back({coord(rng) * 5, row(rng) / 10});
  const PointSet points = WhiteNoise(700, 9);
  const Comparison r = Compare(k, points);
  EXPECT_LT(r.spectrum_error, kRequired);
  EXPECT_LT(r.gradient_error, kRequired);
}

TEST(FastEngineTest, ToleranceSetsKernelWidthAndAccuracy) {
  const std::vector<Frequency> k =
      BuildFrequencySet(DefaultFrequencyParams(512), AnisotropyDirections({70.0}));
  const PointSet points = OwenScrambledSobol(512, 2);
  EXPECT_LT(FastEngine(1, 1e-4).kernel_width(), FastEngine(1, 1e-12).kernel_width());
  const Comparison loose = Compare(k, points, 1e-4);
  const Comparison tight = Compare(k, points, 1e-12);
  EXPECT_LT(loose.spectrum_error, 1e-3);
  EXPECT_LT(loose.gradient_error, 1e-3);
  EXPECT_LT(tight.spectrum_error, 1e-10);
  EXPECT_LT(tight.gradient_error, 1e-10);
  // The loose kernel really is coarser (otherwise the width would not
  // follow the tolerance).
  EXPECT_GT(loose.spectrum_error, 100 * tight.spectrum_error);
}

TEST(FastEngineTest, ResultsDoNotDependOnTheThreadCount) {
  const std::vector<Frequency> k =
      BuildFrequencySet(DefaultFrequencyParams(2000), AnisotropyDirections({33.0, 100.0}));
  const PointSet points = WhiteNoise(2000, 4);
  SpectrumEvaluation one, three;
  FastEngine a(1), b(3);
  a.SetFrequencies(k);
  b.SetFrequencies(k);
  a.Evaluate(points, true, &one);
  b.Evaluate(points, true, &three);
  ASSERT_EQ(one.spectrum.size(), three.spectrum.size());
  for (size_t i = 0; i < one.spectrum.size(); ++i) ASSERT_EQ(one.spectrum[i], three.spectrum[i]);
  for (size_t j = 0; j < one.gradient.size(); ++j) ASSERT_EQ(one.gradient[j], three.gradient[j]);
  EXPECT_EQ(one.loss, three.loss);
}

TEST(FastEngineTest, RecomputedWeightsGiveTheSameResult) {
  // Large N recomputes the kernel weights in the type-2 pass instead of
  // keeping them; a zero budget forces that path.
  const std::vector<Frequency> k =
      BuildFrequencySet(DefaultFrequencyParams(3000), AnisotropyDirections({125.0}));
  const PointSet points = WhiteNoise(3000, 8);
  FastEngine kept(2), recomputed(2, FastEngine::kDefaultTolerance, 0);
  kept.SetFrequencies(k);
  recomputed.SetFrequencies(k);
  SpectrumEvaluation a, b;
  kept.Evaluate(points, true, &a);
  recomputed.Evaluate(points, true, &b);
  for (size_t i = 0; i < k.size(); ++i) ASSERT_EQ(a.spectrum[i], b.spectrum[i]);
  for (size_t j = 0; j < points.size(); ++j) ASSERT_EQ(a.gradient[j], b.gradient[j]);
}

TEST(FastEngineTest, ReusesPlansAcrossPointSetsAndSizes) {
  // One engine, several evaluations with different point counts.
  const std::vector<Frequency> k =
      BuildFrequencySet(DefaultFrequencyParams(600), AnisotropyDirections({50.0}));
  FastEngine fast(2);
  DirectEngine direct(1);
  fast.SetFrequencies(k);
  direct.SetFrequencies(k);
  for (size_t n : {600u, 37u, 1200u}) {
    const PointSet points = WhiteNoise(n, static_cast<uint32_t>(n));
    SpectrumEvaluation want, got;
    direct.Evaluate(points, true, &want);
    fast.Evaluate(points, n != 37, &got);
    EXPECT_LT(RelativeError(got.spectrum, want.spectrum), kRequired);
    if (n != 37) {
      EXPECT_LT(RelativeError(got.gradient, want.gradient), kRequired);
    } else {
      EXPECT_TRUE(got.gradient.empty());
    }
  }
}

TEST(FastEngineTest, SetToleranceRebuildsForTheBoundKAndKeepsTheWeights) {
  // The optimizer asks a bound engine for its descent tolerance: the engine
  // must then compute exactly what a fresh engine at that tolerance does,
  // with K and the loss weights kept, and come back bit for bit when the
  // full accuracy is asked for again.
  const std::vector<Frequency> k =
      BuildFrequencySet(DefaultFrequencyParams(700), AnisotropyDirections({52.0}));
  std::vector<double> w;
  for (const Frequency& v : k) w.push_back(std::pow(std::hypot(v.a, v.b), -2.5));
  const PointSet points = OwenScrambledSobol(700, 4);
  auto evaluate = [&](FastEngine& e) {
    SpectrumEvaluation out;
    e.Evaluate(points, true, &out);
    return out;
  };
  FastEngine fresh_tight(2), fresh_loose(2, 1e-8), engine(2);
  for (FastEngine* e : {&fresh_tight, &fresh_loose, &engine}) {
    e->SetFrequencies(k);
    e->SetLossWeights(w);
  }
  const SpectrumEvaluation tight = evaluate(fresh_tight), loose = evaluate(fresh_loose);
  engine.SetTolerance(1e-8);
  EXPECT_EQ(engine.kernel_width(), fresh_loose.kernel_width());
  EXPECT_LT(engine.kernel_width(), fresh_tight.kernel_width());
  const SpectrumEvaluation asked = evaluate(engine);
  EXPECT_EQ(asked.loss, loose.loss);
  EXPECT_EQ(asked.spectrum, loose.spectrum);
  EXPECT_EQ(asked.gradient, loose.gradient);
  // Coarser, but within what was asked of it (and the weights still apply:
  // the weighted loss of the tight engine, not the flat one).
  EXPECT_GT(RelativeError(asked.spectrum, tight.spectrum), 1e-12);
  EXPECT_LT(RelativeError(asked.spectrum, tight.spectrum), 1e-7);
  EXPECT_LT(RelativeError(asked.gradient, tight.gradient), 1e-6);
  EXPECT_LT(std::abs(asked.loss - tight.loss) / tight.loss, 1e-6);
  engine.SetTolerance(FastEngine::kDefaultTolerance);
  const SpectrumEvaluation back = evaluate(engine);
  EXPECT_EQ(back.loss, tight.loss);
  EXPECT_EQ(back.gradient, tight.gradient);
}

TEST(FastEngineTest, LossWeightsMatchTheDirectEngine) {
  const std::vector<Frequency> k =
      BuildFrequencySet(DefaultFrequencyParams(1500), AnisotropyDirections({38.0}));
  std::vector<double> w;
  for (const Frequency& v : k) w.push_back(std::pow(std::hypot(v.a, v.b), -2.5));
  const PointSet points = OwenScrambledSobol(1500, 6);
  for (size_t budget : {FastEngine::kWeightBudgetBytes, size_t{0}}) {
    SCOPED_TRACE("weight budget " + std::to_string(budget));
    DirectEngine direct(2);
    FastEngine fast(2, FastEngine::kDefaultTolerance, budget);
    direct.SetFrequencies(k);
    fast.SetFrequencies(k);
    direct.SetLossWeights(w);
    fast.SetLossWeights(w);
    SpectrumEvaluation want, got, unweighted;
    direct.Evaluate(points, true, &want);
    fast.Evaluate(points, true, &got);
    EXPECT_LT(RelativeError(got.gradient, want.gradient), kRequired);
    EXPECT_LT(std::abs(got.loss - want.loss) / want.loss, kRequired);
    // SetFrequencies resets the weights to 1.
    fast.SetFrequencies(k);
    fast.Evaluate(points, true, &unweighted);
    EXPECT_GT(std::abs(unweighted.loss - got.loss), 0.1 * got.loss);
  }
}

TEST(FastEngineTest, WeightedSpectrumMatchesTheDirectEngine) {
  // Disk frequencies only (direction estimation's kind of K) and a full K.
  const std::vector<std::vector<Frequency>> sets = {
      BuildFrequencySet({1, 1, 20}, {}),
      BuildFrequencySet(DefaultFrequencyParams(900), AnisotropyDirections({71.0}))};
  const PointSet points = WhiteNoise(900, 12);
  std::vector<double> f;
  for (const Point2& p : points) f.push_back(p.x + p.y > 1.0 ? 1.0 : -0.5 + p.x * p.y);
  for (const auto& k : sets) {
    for (size_t budget : {FastEngine::kWeightBudgetBytes, size_t{0}}) {
      DirectEngine direct(2);
      FastEngine fast(2, FastEngine::kDefaultTolerance, budget);
      direct.SetFrequencies(k);
      fast.SetFrequencies(k);
      std::vector<std::complex<double>> want, got;
      direct.EvaluateWeighted(points, f, &want);
      fast.EvaluateWeighted(points, f, &got);
      EXPECT_LT(RelativeError(got, want), kRequired) << "|K| " << k.size();
      // A plain evaluation afterwards is unaffected by the strengths.
      SpectrumEvaluation plain_fast, plain_direct;
      fast.Evaluate(points, true, &plain_fast);
      direct.Evaluate(points, true, &plain_direct);
      EXPECT_LT(RelativeError(plain_fast.spectrum, plain_direct.spectrum), kRequired);
      EXPECT_LT(RelativeError(plain_fast.gradient, plain_direct.gradient), kRequired);
    }
  }
}

TEST(FastEngineTest, EmptyInputs) {
  FastEngine fast(2);
  SpectrumEvaluation out;
  fast.SetFrequencies({});
  fast.Evaluate(WhiteNoise(10, 1), true, &out);
  EXPECT_TRUE(out.spectrum.empty());
  EXPECT_EQ(out.loss, 0.0);
  ASSERT_EQ(out.gradient.size(), 10u);
  for (const Point2& g : out.gradient) EXPECT_EQ(g, (Point2{0.0, 0.0}));

  fast.SetFrequencies({{1, 2}, {3, 0}});
  fast.Evaluate({}, true, &out);
  ASSERT_EQ(out.spectrum.size(), 2u);
  EXPECT_EQ(out.spectrum[0], std::complex<double>(0.0));
  EXPECT_EQ(out.loss, 0.0);
  EXPECT_TRUE(out.gradient.empty());
}

TEST(EngineFactoryTest, BuildsEveryKindOrExplains) {
  auto fast = MakeSpectralEngine(EngineKind::kFast, 2);
  ASSERT_TRUE(fast.ok());
  EXPECT_EQ((*fast)->name(), "fast");
  auto direct = MakeSpectralEngine(EngineKind::kDirect, 2);
  ASSERT_TRUE(direct.ok());
  EXPECT_EQ((*direct)->name(), "direct");
  auto cuda = MakeSpectralEngine(EngineKind::kCuda, 2);
  auto automatic = MakeSpectralEngine(EngineKind::kAuto, 2);
  ASSERT_TRUE(automatic.ok());
  if (cuda.ok()) {
    EXPECT_EQ((*automatic)->name(), "cuda");
  } else {
    EXPECT_EQ(cuda.status().code(), Status::Code::kUnavailable);
    EXPECT_NE(cuda.status().message().find("CUDA"), std::string::npos);
    EXPECT_EQ((*automatic)->name(), "fast");
  }
  auto bad = ParseEngineKind("gpu");
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(bad.status().message().find("fast"), std::string::npos);
}

}  // namespace
}  // namespace alignset

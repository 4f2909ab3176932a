// The CUDA engine against the direct engine. Runs only where the engine is
// built and a CUDA device is present; skips (with the reason) elsewhere.
#include <gtest/gtest.h>

#include "tests/core/spectral/relative_error.h"

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "core/spectral/direct_engine.h"
#include "core/spectral/frequency_set.h"
#include "core/sampling/owen_sobol.h"
#include "core/spectral/spectral_engine.h"
#ifdef ALIGNSET_HAVE_CUDA
#include "core/spectral/cuda/cuda_engine.h"
#endif

namespace alignset {
namespace {

// The CUDA engine, or the reason the test cannot run here.
std::unique_ptr<SpectralEngine> CudaOrReason(std::string* reason) {
#ifndef ALIGNSET_HAVE_CUDA
  *reason = "the CUDA engine is not built in this binary (ALIGNSET_CUDA=OFF or no nvcc found)";
  return nullptr;
#else
  auto engine = MakeSpectralEngine(EngineKind::kCuda, 2);
  if (!engine.ok()) {
    *reason = engine.status().message();
    return nullptr;
  }
  return std::move(engine).value();
#endif
}

using test_support::RelativeError;

TEST(CudaEngineTest, UnavailableWithAReasonWhenNoDevice) {
  std::string reason;
  auto engine = CudaOrReason(&reason);
  if (engine) GTEST_SKIP() << "a CUDA device is present; this checks the no-device path";
  auto made = MakeSpectralEngine(EngineKind::kCuda, 2);
  ASSERT_FALSE(made.ok());
  EXPECT_EQ(made.status().code(), Status::Code::kUnavailable);
  EXPECT_NE(made.status().message().find("CUDA"), std::string::npos);
  // auto falls back to the fast CPU engine.
  auto automatic = MakeSpectralEngine(EngineKind::kAuto, 2);
  ASSERT_TRUE(automatic.ok());
  EXPECT_EQ((*automatic)->name(), "fast");
}

TEST(CudaEngineTest, MatchesDirect) {
  std::string reason;
  auto cuda = CudaOrReason(&reason);
  if (!cuda) GTEST_SKIP() << reason;
  EXPECT_EQ(cuda->name(), "cuda");
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (uint32_t n : {16u, 300u, 4096u}) {
    const std::vector<std::vector<double>> direction_sets = {{30.0}, {115.0, 160.0}};
    for (const std::vector<double>& dirs : direction_sets) {
      const std::vector<Frequency> k =
          BuildFrequencySet(DefaultFrequencyParams(n), AnisotropyDirections(dirs));
      PointSet points = OwenScrambledSobol(n, 3);
      if (n == 300) {
        for (Point2& p : points) p = {u(rng), u(rng)};
      }
      DirectEngine direct(2);
      direct.SetFrequencies(k);
      cuda->SetFrequencies(k);
      SpectrumEvaluation want, got;
      direct.Evaluate(points, true, &want);
      cuda->Evaluate(points, true, &got);
      ASSERT_EQ(got.spectrum.size(), k.size());
      ASSERT_EQ(got.gradient.size(), points.size());
      EXPECT_LT(RelativeError(got.spectrum, want.spectrum), 1e-9) << n;
      EXPECT_LT(RelativeError(got.gradient, want.gradient), 1e-9) << n;
      EXPECT_NEAR(got.loss, want.loss, 1e-9 * want.loss) << n;
    }
  }
}

TEST(CudaEngineTest, LossWeightsAndStrengthsMatchDirect) {
  std::string reason;
  auto cuda = CudaOrReason(&reason);
  if (!cuda) GTEST_SKIP() << reason;
  const uint32_t n = 2048;
  const std::vector<Frequency> k =
      BuildFrequencySet(DefaultFrequencyParams(n), AnisotropyDirections({52.0}));
  std::vector<double> w;
  for (const Frequency& v : k) w.push_back(std::pow(std::hypot(v.a, v.b), -3.0));
  const PointSet points = OwenScrambledSobol(n, 4);
  std::vector<double> f;
  for (const Point2& p : points) f.push_back(std::cos(6.0 * p.x) - p.y);
  DirectEngine direct(2);
  direct.SetFrequencies(k);
  cuda->SetFrequencies(k);
  direct.SetLossWeights(w);
  cuda->SetLossWeights(w);
  SpectrumEvaluation want, got;
  direct.Evaluate(points, true, &want);
  cuda->Evaluate(points, true, &got);
  EXPECT_LT(RelativeError(got.gradient, want.gradient), 1e-9);
  EXPECT_NEAR(got.loss, want.loss, 1e-9 * want.loss);
  std::vector<std::complex<double>> fw, fg;
  direct.EvaluateWeighted(points, f, &fw);
  cuda->EvaluateWeighted(points, f, &fg);
  EXPECT_LT(RelativeError(fg, fw), 1e-9);
}

TEST(CudaEngineTest, EmptyInputsAndDeterminism) {
  std::string reason;
  auto cuda = CudaOrReason(&reason);
  if (!cuda) GTEST_SKIP() << reason;
  SpectrumEvaluation out;
  cuda->SetFrequencies({});
  cuda->Evaluate(OwenScrambledSobol(8, 1), true, &out);
  EXPECT_TRUE(out.spectrum.empty());
  EXPECT_EQ(out.gradient.size(), 8u);
  const std::vector<Frequency> k =
      BuildFrequencySet(DefaultFrequencyParams(1024), AnisotropyDirections({70.0}));
  cuda->SetFrequencies(k);
  const PointSet points = OwenScrambledSobol(1024, 9);
  SpectrumEvaluation a, b;
  cuda->Evaluate(points, true, &a);
  cuda->Evaluate(points, true, &b);
  for (size_t i = 0; i < k.size(); ++i) ASSERT_EQ(a.spectrum[i], b.spectrum[i]);
  for (size_t j = 0; j < points.size(); ++j) ASSERT_EQ(a.gradient[j], b.gradient[j]);
}

}  // namespace
}  // namespace alignset

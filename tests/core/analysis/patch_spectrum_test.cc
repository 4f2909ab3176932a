#include "core/analysis/patch_spectrum.h"

#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <limits>

#include "core/spectral/direct_engine.h"
#include "core/spectral/fast_engine.h"
#include "core/util/angles.h"
#include "core/util/hash.h"

namespace alignset {
namespace {

GridPatch RandomGrid(int w, int h, uint64_t seed) {
  Pcg32 rng(seed);
  GridPatch g{w, h, std::vector<double>(static_cast<size_t>(w) * h)};
  for (double& v : g.values) v = rng.NextDouble();
  return g;
}

TEST(TukeyWindow, EndsHannAndFlat) {
  EXPECT_EQ(TukeyWindow(0.0, 0.5), 0.0);
  EXPECT_EQ(TukeyWindow(1.0, 0.5), 0.0);
  EXPECT_EQ(TukeyWindow(0.5, 0.5), 1.0);
  EXPECT_EQ(TukeyWindow(0.3, 0.5), 1.0);  // flat beyond the 0.25 taper
  EXPECT_NEAR(TukeyWindow(0.125, 0.5), 0.5, 1e-15);
  for (double u : {0.1, 0.3, 0.77}) {
    EXPECT_NEAR(TukeyWindow(u, 1.0), 0.5 - 0.5 * std::cos(2 * kPi * u), 1e-15) << u;
    EXPECT_EQ(TukeyWindow(u, 0.0), 1.0);
  }
}

TEST(PatchSpectrum, GridFftMatchesTheEngineAtCellCentres) {
  // A non-square, non-power-of-two grid: the FFT path and the type-1 sum at
  // the cell centres give the same power.
  const GridPatch g = RandomGrid(30, 18, 4);
  SpectrumOptions o;
  auto fft = GridPowerSpectrum(g, o);
  ASSERT_TRUE(fft.ok()) << fft.status().message();
  DirectEngine direct(1);
  FastEngine fast(1);
  auto d = GridPowerSpectrumByEngine(g, o, &direct);
  auto f = GridPowerSpectrumByEngine(g, o, &fast);
  ASSERT_TRUE(d.ok() && f.ok());
  ASSERT_EQ(fft->frequencies, d->frequencies);
  ASSERT_EQ(fft->max_radius, std::floor(7.0 / 16.0 * 18));
  double scale = 0;
  for (double p : d->power) scale = std::max(scale, p);
  for (size_t k = 0; k < d->power.size(); ++k) {
    EXPECT_NEAR(fft->power[k], d->power[k], 1e-12 * scale) << k;
    EXPECT_NEAR(f->power[k], d->power[k], 1e-9 * scale) << k;
  }
}

TEST(PatchSpectrum, SamplesMatchANaiveSum) {
  Pcg32 rng(9);
  SampledPatch s;
  for (int j = 0; j < 200; ++j) {
    s.points.push_back({rng.NextDouble(), rng.NextDouble()});
    s.values.push_back(std::sin(7 * s.points.back().x) + rng.NextDouble());
  }
  s.points.push_back({1.0, 0.0});  // the closed square is allowed
  s.values.push_back(3.0);
  SpectrumOptions o;
  o.max_radius = 9;
  auto spec = SampledPowerSpectrum(s, o, nullptr);
  ASSERT_TRUE(spec.ok()) << spec.status().message();
  double mean = 0;
  for (double v : s.values) mean += v;
  mean /= s.values.size();
  const double m = static_cast<double>(s.points.size());
  double floor = 0;
  for (size_t k = 0; k < spec->frequencies.size(); ++k) {
    const Frequency v = spec->frequencies[k];
    EXPECT_GE(v.a * v.a + v.b * v.b, 4);
    EXPECT_LE(v.a * v.a + v.b * v.b, 81);
    std::complex<double> sum = 0;
    floor = 0;
    for (size_t j = 0; j < s.points.size(); ++j) {
      const Point2 p = s.points[j];
      const double g = (s.values[j] - mean) * TukeyWindow(p.x, 0.5) * TukeyWindow(p.y, 0.5) / m;
      floor += g * g;
      sum += g * std::exp(std::complex<double>(0, -2 * kPi * (v.a * p.x + v.b * p.y)));
    }
    EXPECT_NEAR(spec->power[k], std::norm(sum), 1e-13) << k;
  }
  EXPECT_NEAR(spec->noise_floor, floor, 1e-15);
  // The fast engine gives the same numbers.
  FastEngine fast(1);
  auto f = SampledPowerSpectrum(s, o, &fast);
  ASSERT_TRUE(f.ok());
  for (size_t k = 0; k < f->power.size(); ++k) EXPECT_NEAR(f->power[k], spec->power[k], 1e-12);
}

TEST(PatchSpectrum, NoiseFloorIsTheMeanPowerOfWhiteNoise) {
  // Random values at random positions: every frequency's expected power is
  // the floor sum_j g_j^2.
  Pcg32 rng(2);
  SampledPatch s;
  for (int j = 0; j < 4096; ++j) {
    s.points.push_back({rng.NextDouble(), rng.NextDouble()});
    s.values.push_back(rng.NextDouble());
  }
  SpectrumOptions o;
  o.max_radius = 24;
  auto spec = SampledPowerSpectrum(s, o, nullptr);
  ASSERT_TRUE(spec.ok());
  double mean = 0;
  for (double p : spec->power) mean += p / spec->power.size();
  EXPECT_NEAR(mean / spec->noise_floor, 1.0, 0.1);
}

TEST(PatchSpectrum, RefusesBadInput) {
  auto code = [](const Status& s) { return s.code(); };
  const auto bad = Status::Code::kInvalidArgument;
  EXPECT_EQ(code(ValidateGridPatch({7, 8, std::vector<double>(56)})), bad);
  EXPECT_EQ(code(ValidateGridPatch({8, 8, std::vector<double>(63)})), bad);
  EXPECT_EQ(code(ValidateGridPatch({5000, 8, std::vector<double>(40000)})), bad);
  EXPECT_EQ(code(ValidateGridPatch({2048, 1024, {}})), bad);  // over 2^20 cells
  GridPatch nan{8, 8, std::vector<double>(64, 1.0)};
  nan.values[9] = std::nan("");
  const Status s = ValidateGridPatch(nan);
  EXPECT_EQ(s.code(), bad);
  EXPECT_NE(s.message().find("row 1, column 1"), std::string::npos) << s.message();
  EXPECT_TRUE(ValidateGridPatch({8, 8, std::vector<double>(64, 1.0)}).ok());

  EXPECT_EQ(code(ValidateSampledPatch({})), bad);
  EXPECT_EQ(code(ValidateSampledPatch({{{0.5, 0.5}}, {1.0, 2.0}})), bad);
  EXPECT_EQ(code(ValidateSampledPatch({{{0.5, 1.5}}, {1.0}})), bad);
  EXPECT_EQ(code(ValidateSampledPatch({{{0.5, std::numeric_limits<double>::infinity()}}, {1.0}})),
            bad);
  EXPECT_EQ(code(ValidateSampledPatch({{{0.5, 0.5}}, {std::nan("")}})), bad);
  EXPECT_TRUE(ValidateSampledPatch({{{0.0, 1.0}}, {1.0}}).ok());

  SpectrumOptions o;
  o.max_radius = 4;  // a 8 x 8 grid's Nyquist radius
  EXPECT_EQ(GridPowerSpectrum({8, 8, std::vector<double>(64)}, o).status().code(), bad);
  o.max_radius = 0;
  o.window_taper = 2;
  EXPECT_EQ(GridPowerSpectrum({8, 8, std::vector<double>(64)}, o).status().code(), bad);
}

}  // namespace
}  // namespace alignset

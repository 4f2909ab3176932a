#include "core/spectral/frequency_set.h"

#include <gtest/gtest.h>

#include <cmath>
#include <set>

namespace alignset {
namespace {

TEST(FrequencySet, TableOneSizesUseTheTableParameters) {
  EXPECT_EQ(SupplementFrequencyParams(4096), (FrequencyParams{256, 5, 24}));
  EXPECT_EQ(SupplementFrequencyParams(8192), (FrequencyParams{384, 7, 32}));
  EXPECT_EQ(SupplementFrequencyParams(16384), (FrequencyParams{512, 9, 48}));
  EXPECT_EQ(SupplementFrequencyParams(32768), (FrequencyParams{768, 13, 56}));
  EXPECT_EQ(SupplementFrequencyParams(65536), (FrequencyParams{1024, 17, 64}));
}

TEST(FrequencySet, CountsMatchTableOneWithinFivePercent) {
  const std::pair<uint32_t, double> rows[] = {
      {4096, 4303}, {8192, 9169}, {16384, 16099}, {32768, 32708}, {65536, 55741}};
  for (double theta : {15.0, 30.0}) {
    for (const auto& [n, expected] : rows) {
      const auto k =
          BuildFrequencySet(SupplementFrequencyParams(n), AnisotropyDirections({theta}));
      EXPECT_NEAR(static_cast<double>(k.size()) / expected, 1.0, 0.05)
          << "N=" << n << " theta=" << theta << " |K|=" << k.size();
    }
  }
}

TEST(FrequencySet, CountStaysCloseToNForEveryN) {
  // The supplement keeps |K| ~ N (ratios 0.85..1.12 in Table 1); its rule for
  // other N must stay in that band, and alignset's wider strips and disk at
  // a fixed multiple of it, so that the cost per iteration scales like N.
  for (uint32_t n : {16u, 24u, 64u, 100u, 256u, 500u, 1000u, 1024u, 3000u, 5000u, 12000u,
                     20000u, 50000u, 100000u}) {
    for (double theta : {10.0, 30.0, 45.0, 77.0}) {
      const auto k =
          BuildFrequencySet(SupplementFrequencyParams(n), AnisotropyDirections({theta}));
      const double ratio = static_cast<double>(k.size()) / n;
      EXPECT_GT(ratio, 0.7) << "N=" << n << " theta=" << theta << " |K|=" << k.size();
      EXPECT_LT(ratio, 1.4) << "N=" << n << " theta=" << theta << " |K|=" << k.size();
      const auto wide = BuildFrequencySet(DefaultFrequencyParams(n), AnisotropyDirections({theta}));
      const double wide_ratio = static_cast<double>(wide.size()) / n;
      EXPECT_GT(wide_ratio, 1.0) << "N=" << n << " theta=" << theta;
      EXPECT_LT(wide_ratio, 2.2) << "N=" << n << " theta=" << theta;
    }
  }
}

TEST(FrequencySet, DefaultsAreTheSupplementsWidened) {
  for (uint32_t n : {16u, 256u, 1024u, 4096u, 65536u}) {
    const FrequencyParams s = SupplementFrequencyParams(n);
    const FrequencyParams d = DefaultFrequencyParams(n);
    EXPECT_EQ(d.length, s.length);
    EXPECT_DOUBLE_EQ(d.width, s.width * kDefaultWidthScale);
    EXPECT_DOUBLE_EQ(d.radius, s.radius * kDefaultRadiusScale);
  }
}

TEST(FrequencySet, HalfPlaneWithoutDcOrDuplicates) {
  const auto k = BuildFrequencySet(DefaultFrequencyParams(1024), AnisotropyDirections({20, 130}));
  std::set<std::pair<int, int>> seen;
  for (const Frequency& v : k) {
    EXPECT_FALSE(v.a == 0 && v.b == 0);
    EXPECT_TRUE(v.b > 0 || (v.b == 0 && v.a > 0)) << v.a << "," << v.b;
    EXPECT_TRUE(seen.insert({v.a, v.b}).second);
    EXPECT_FALSE(seen.count({-v.a, -v.b}));
  }
}

TEST(FrequencySet, StripsAreTheDefinedSets) {
  const FrequencyParams p{40, 5, 3};
  // The 0° strip: |a| <= 40, |b| <= 2.5, canonical half.
  const auto axis = StripFrequencies(p, 0.0);
  EXPECT_EQ(axis.size(), (81u * 5u - 1u) / 2u);
  for (const Frequency& v : axis) {
    EXPECT_LE(std::abs(v.a), 40);
    EXPECT_LE(std::abs(v.b), 2);
  }
  // An oblique strip holds about length * width frequencies (half of 2L x W).
  for (double theta : {10.0, 30.0, 45.0, 100.0, 160.0}) {
    const auto s = StripFrequencies(p, theta);
    EXPECT_NEAR(static_cast<double>(s.size()), p.length * p.width, 0.1 * p.length * p.width)
        << theta;
    const double c = std::cos(theta * M_PI / 180), sn = std::sin(theta * M_PI / 180);
    for (const Frequency& v : s) {
      EXPECT_LE(std::abs(v.a * c + v.b * sn), p.length + 1e-9);
      EXPECT_LE(std::abs(-v.a * sn + v.b * c), p.width / 2 + 1e-9);
    }
  }
}

TEST(FrequencySet, DirectionsAreReducedAndAlwaysIncludeTheAxes) {
  const auto d = AnisotropyDirections({-30, 400});
  ASSERT_EQ(d.size(), 4u);
  EXPECT_EQ(d[0], 0.0);
  EXPECT_EQ(d[1], 90.0);
  EXPECT_DOUBLE_EQ(d[2], 150.0);
  EXPECT_DOUBLE_EQ(d[3], 40.0);
  // A direction and its opposite give the same strip.
  EXPECT_EQ(StripFrequencies({30, 3, 2}, 25), StripFrequencies({30, 3, 2}, 205));
}

TEST(FrequencySet, ValidationRejectsNonsense) {
  EXPECT_FALSE(ValidateFrequencyParams({NAN, 1, 1}).ok());
  EXPECT_FALSE(ValidateFrequencyParams({-1, 1, 1}).ok());
  EXPECT_FALSE(ValidateFrequencyParams({1e9, 1, 1}).ok());
  EXPECT_TRUE(ValidateFrequencyParams(DefaultFrequencyParams(65536)).ok());
}

}  // namespace
}  // namespace alignset

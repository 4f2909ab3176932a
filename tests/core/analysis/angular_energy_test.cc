#include "core/analysis/angular_energy.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/util/angles.h"
#include "core/util/hash.h"

namespace alignset {
namespace {

TEST(AngularEnergy, ProfileIsAtOnTheBinCentres) {
  Pcg32 rng(1);
  std::vector<Frequency> k;
  std::vector<double> w;
  for (int b = 0; b <= 12; ++b) {
    for (int a = -12; a <= 12; ++a) {
      if ((b == 0 && a <= 0) || a * a + b * b > 144 || a * a + b * b < 4) continue;
      k.push_back({a, b});
      w.push_back(rng.NextDouble());
    }
  }
  const AngularEnergy e(k, w, 1.0);
  const int bins = 360;
  const auto profile = e.Profile(bins);
  for (int i = 0; i < bins; i += 7) {
    EXPECT_NEAR(profile[i], e.At((i + 0.5) * kPi / bins), 1e-12 * profile[i]) << i;
  }
  // WeightNear as a profile and one at a time.
  const auto near = e.WeightNearProfile(0.2, bins);
  for (int i = 0; i < bins; i += 11) {
    EXPECT_NEAR(near[i], e.WeightNear((i + 0.5) * kPi / bins, 0.2), 1e-12) << i;
  }
}

TEST(AngularEnergy, ALineOfFrequenciesPeaksOnItsAngle) {
  // Frequencies along the direction (3, 1), 18.43°, carry all the weight.
  std::vector<Frequency> k;
  std::vector<double> w;
  for (int t = 1; t <= 8; ++t) {
    k.push_back({3 * t, t});
    w.push_back(1.0);
    k.push_back({t, 5});  // and some off the line with no weight
    w.push_back(0.0);
  }
  const AngularEnergy e(k, w, 1.0);
  const double theta = std::atan2(1.0, 3.0);
  EXPECT_GT(e.At(theta), e.At(theta + 0.01));
  EXPECT_GT(e.At(theta), e.At(theta - 0.01));
  EXPECT_NEAR(e.At(theta), 8.0, 1e-12);
  EXPECT_NEAR(e.At(theta + kPi), 8.0, 1e-12);  // axial
  EXPECT_EQ(e.TotalWeight(), 8.0);
  EXPECT_EQ(e.WeightNear(theta, 1e-9), 8.0);
  EXPECT_TRUE(NearLine({30, 10}, theta, 0.5));
  EXPECT_FALSE(NearLine({30, 12}, theta, 0.5));
  EXPECT_TRUE(NearLine({1, 1}, theta, 4.0));  // low rings: every angle
}

}  // namespace
}  // namespace alignset

// How the strips of sets with 3 to 8 arbitrary directions share the budget.
#include "core/spectral/direction_budget.h"

#include <gtest/gtest.h>

#include <vector>

#include "core/spectral/frequency_set.h"

namespace alignset {
namespace {

TEST(DirectionBudget, OneAndTwoDirectionsKeepTheDefaults) {
  for (uint32_t n : {16u, 256u, 1000u, 4096u, 65536u}) {
    EXPECT_EQ(FrequencyParamsForDirections(n, 1), DefaultFrequencyParams(n)) << n;
    EXPECT_EQ(FrequencyParamsForDirections(n, 2), DefaultFrequencyParams(n)) << n;
  }
}

TEST(DirectionBudget, MoreDirectionsShareTheTwoDirectionStripBudget) {
  for (uint32_t n : {256u, 1024u, 4096u, 16384u}) {
    const FrequencyParams base = DefaultFrequencyParams(n);
    FrequencyParams previous = base;
    for (int k = 3; k <= kMaxArbitraryDirections; ++k) {
      const FrequencyParams p = FrequencyParamsForDirections(n, k);
      const double strips = 2.0 + k;
      EXPECT_EQ(p.radius, base.radius);
      // Each strip gets 4 / D of a default strip's frequencies (L W), unless
      // the floors (length >= radius) bind.
      if (p.length > p.radius) {
        EXPECT_NEAR(p.length * p.width, base.length * base.width * 4.0 / strips,
                    1e-9 * base.length * base.width);
      }
      EXPECT_GE(p.width, previous.width) << n << " k=" << k;
      EXPECT_LT(p.length, previous.length) << n << " k=" << k;
      EXPECT_GE(p.length, p.radius);
      previous = p;
    }
  }
}

TEST(DirectionBudget, TheFrequencyCountStaysNearTheTwoDirectionCount) {
  // Directions spread over the half turn, as in the polygon figure.
  for (uint32_t n : {256u, 1024u, 4096u}) {
    const size_t two = BuildFrequencySet(DefaultFrequencyParams(n), {0, 90, 30, 120}).size();
    for (int k = 3; k <= kMaxArbitraryDirections; ++k) {
      std::vector<double> dirs = {0, 90};
      for (int i = 0; i < k; ++i) dirs.push_back(7.0 + 180.0 * i / k);
      const size_t count = BuildFrequencySet(FrequencyParamsForDirections(n, k), dirs).size();
      // Shared, not multiplied: within 0.5 .. 1.3 of the two-direction set's
      // |K| (the strips overlap each other and the disk near the centre, more
      // so the more there are: 0.59 at k = 8, N = 4096).
      EXPECT_GT(count, 0.5 * two) << n << " k=" << k;
      EXPECT_LT(count, 1.3 * two) << n << " k=" << k;
    }
  }
}

}  // namespace
}  // namespace alignset

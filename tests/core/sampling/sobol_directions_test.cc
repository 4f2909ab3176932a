// The many-dimensional Sobol sequence's direction numbers, against what they
// must give: owen_sobol.h's two dimensions bit for bit, Boost.Random's own
// generator point for point (its sequence runs in Gray-code order and skips
// point 0), and in every dimension the first 2^m points are the 2^m strata.
#include "core/sampling/sobol_directions.h"

#include <gtest/gtest.h>

#include <boost/random/sobol.hpp>

#include <vector>

#include "core/sampling/owen_sobol.h"

namespace alignset {
namespace {

TEST(SobolDirections, TheFirstTwoDimensionsAreOwenSobolsDigitForDigit) {
  const std::vector<uint32_t> v = SobolDirectionNumbers(2);
  ASSERT_EQ(v.size(), 2 * kSobolDigits);
  for (uint32_t i = 0; i < (1u << 16); ++i) {
    ASSERT_EQ(SobolDigits(&v[0], i), SobolDim0(i)) << i;
    ASSERT_EQ(SobolDigits(&v[kSobolDigits], i), SobolDim1(i)) << i;
  }
  EXPECT_EQ(SobolDigits(&v[0], 0xffffffffu), SobolDim0(0xffffffffu));
}

TEST(SobolDirections, AgreeWithBoostsGeneratorInEveryDimension) {
  constexpr uint32_t kDims = 200;
  const std::vector<uint32_t> v = SobolDirectionNumbers(kDims);
  boost::random::sobol_engine<uint32_t, 32> engine(kDims);
  for (uint32_t n = 0; n < 4096; ++n) {
    const uint32_t gray = (n + 1) ^ ((n + 1) >> 1);
    for (uint32_t d = 0; d < kDims; ++d) {
      ASSERT_EQ(engine(), SobolDigits(&v[d * kSobolDigits], gray)) << "point " << n << " dimension " << d;
    }
  }
}

TEST(SobolDirections, EveryDimensionsFirstPowerOfTwoPointsAreItsStrata) {
  const std::vector<uint32_t> v = SobolDirectionNumbers(kSobolMaxDimensions);
  ASSERT_EQ(v.size(), size_t{kSobolMaxDimensions} * kSobolDigits);
  for (uint32_t d = 0; d < kSobolMaxDimensions; d += (d < 64 ? 1 : 97)) {
    for (uint32_t m : {1u, 4u, 10u}) {
      std::vector<int> hit(1u << m, 0);
      for (uint32_t i = 0; i < (1u << m); ++i) ++hit[SobolDigits(&v[d * kSobolDigits], i) >> (32 - m)];
      for (uint32_t s = 0; s < (1u << m); ++s) ASSERT_EQ(hit[s], 1) << "dimension " << d << " m " << m;
    }
  }
  EXPECT_TRUE(SobolDirectionNumbers(0).empty());
}

}  // namespace
}  // namespace alignset

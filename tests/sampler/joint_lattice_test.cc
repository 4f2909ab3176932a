// The joint rank-1 lattice over a camera sample's leading dimensions, against
// its mathematical properties: each lattice dimension is the N strata, the
// component-by-component generator is the best one for each new component,
// every value is uniform (unbiased estimates, padding included), and joint
// stratification beats the same dimensions paired at random.
#include <alignset/joint_lattice.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <vector>

namespace alignset {
namespace {

TEST(JointLattice, RefusesSizesItCannotMake) {
  EXPECT_FALSE(JointLattice::Create(1, 3, 1).ok());
  EXPECT_FALSE(JointLattice::Create(65537, 3, 1).ok());
  EXPECT_FALSE(JointLattice::Create(256, 0, 1).ok());
  auto too_many = JointLattice::Create(256, kJointLatticeMaxDimensions + 1, 1);
  ASSERT_FALSE(too_many.ok());
  EXPECT_NE(too_many.status().message().find("dimensions must be in [1, 16]"), std::string::npos);
}

TEST(JointLattice, EveryLatticeDimensionIsTheNStrataInEveryPixel) {
  for (uint32_t n : {64u, 192u, 256u, 1000u}) {
    auto l = JointLattice::Create(n, 5, 7);
    ASSERT_TRUE(l.ok());
    EXPECT_EQ(l->generator()[0], 1u);
    for (uint32_t z : l->generator()) EXPECT_EQ(std::gcd(z, n), 1u) << "N=" << n;
    for (uint64_t pixel : {0ull, 5ull, 123456ull}) {
      for (uint32_t d = 0; d < 5; ++d) {
        std::vector<int> hit(n, 0);
        for (uint32_t i = 0; i < n; ++i) {
          const double x = l->Sample(pixel, i, d);
          ASSERT_GE(x, 0.0);
          ASSERT_LT(x, 1.0);
          ++hit[static_cast<size_t>(x * n)];
        }
        EXPECT_TRUE(std::all_of(hit.begin(), hit.end(), [](int h) { return h == 1; }))
            << "N=" << n << " pixel " << pixel << " dimension " << d;
      }
    }
  }
}

TEST(JointLattice, EachComponentIsTheBestForTheOnesBeforeIt) {
  // Brute force over every candidate of the last component: the CBC choice
  // has the least P_2 (ties: the smaller candidate).
  for (uint32_t n : {64u, 101u, 256u}) {
    auto l = JointLattice::Create(n, 3, 1);
    ASSERT_TRUE(l.ok());
    const std::vector<uint32_t> z = l->generator();
    const double chosen = JointLatticeP2(n, z);
    for (uint32_t c = 1; c < n; ++c) {
      if (std::gcd(c, n) != 1) continue;
      std::vector<uint32_t> other = {z[0], z[1], c};
      EXPECT_LE(chosen, JointLatticeP2(n, other) * (1.0 + 1e-12)) << "N=" << n << " c=" << c;
    }
    // and far below a typical generator's
    double mean = 0.0;
    int count = 0;
    for (uint32_t c = 1; c < n; c += 7) {
      if (std::gcd(c, n) != 1) continue;
      mean += JointLatticeP2(n, {1, c, (c * 5 + 3) % n == 0 ? 1 : (c * 5 + 3) % n});
      ++count;
    }
    EXPECT_LT(chosen, 0.5 * mean / count) << "N=" << n;
  }
}

TEST(JointLattice, DeterministicInSeedPixelSampleAndDimension) {
  auto a = JointLattice::Create(256, 3, 42), b = JointLattice::Create(256, 3, 42), c = JointLattice::Create(256, 3, 43);
  ASSERT_TRUE(a.ok() && b.ok() && c.ok());
  for (uint32_t d = 0; d < 6; ++d) {
    EXPECT_EQ(a->Sample(9, 17, d), b->Sample(9, 17, d));
    EXPECT_NE(a->Sample(9, 17, d), c->Sample(9, 17, d));
    EXPECT_NE(a->Sample(9, 17, d), a->Sample(10, 17, d));
  }
}

// A smooth integrand that is not periodic on the unit cube, over five
// dimensions (three on the lattice, two padded), and its exact integral.
double F(const double* x) {
  return std::exp(0.8 * x[0] - 0.5 * x[1]) * (1.0 + x[2] * x[2]) * (0.5 + x[3]) * (1.5 - x[4] * x[4]);
}
double Exact() {
  const double a = (std::exp(0.8) - 1.0) / 0.8, b = (1.0 - std::exp(-0.5)) / 0.5;
  return a * b * (4.0 / 3.0) * 1.0 * (1.5 - 1.0 / 3.0);
}

TEST(JointLattice, EveryPixelsEstimateIsUnbiasedPaddingIncluded) {
  constexpr uint32_t kN = 64, kPixels = 4000;
  auto l = JointLattice::Create(kN, 3, 5);
  ASSERT_TRUE(l.ok());
  double sum = 0.0, sum2 = 0.0;
  for (uint64_t p = 0; p < kPixels; ++p) {
    double est = 0.0;
    for (uint32_t i = 0; i < kN; ++i) {
      double x[5];
      for (uint32_t d = 0; d < 5; ++d) x[d] = l->Sample(p, i, d);
      est += F(x);
    }
    est /= kN;
    sum += est;
    sum2 += est * est;
  }
  const double mean = sum / kPixels, var = sum2 / kPixels - mean * mean;
  const double se = std::sqrt(var / kPixels);
  EXPECT_NEAR(mean, Exact(), 3.0 * se + 1e-12) << "standard error " << se;
}

TEST(JointLattice, JointStratificationBeatsRandomPairing) {
  // The same integrand of the three lattice dimensions: the joint lattice
  // against each dimension padded (stratified alone, paired at random).
  constexpr uint32_t kN = 256, kPixels = 400;
  auto l = JointLattice::Create(kN, 3, 9);
  ASSERT_TRUE(l.ok());
  auto variance = [&](uint32_t first_dim) {
    double sum = 0.0, sum2 = 0.0;
    for (uint64_t p = 0; p < kPixels; ++p) {
      double est = 0.0;
      for (uint32_t i = 0; i < kN; ++i) {
        double x[5] = {l->Sample(p, i, first_dim), l->Sample(p, i, first_dim + 1), l->Sample(p, i, first_dim + 2),
                       0.5, 0.5};
        est += F(x);
      }
      est /= kN;
      sum += est;
      sum2 += est * est;
    }
    const double mean = sum / kPixels;
    return sum2 / kPixels - mean * mean;
  };
  const double joint = variance(0), padded = variance(3);
  EXPECT_LT(joint, 0.25 * padded) << "joint " << joint << ", padded " << padded;
}

}  // namespace
}  // namespace alignset

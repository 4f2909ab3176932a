#include "core/sampling/pmj02.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "core/sampling/sampler_util.h"

namespace alignset {
namespace {

bool Stratified(const PointSet& p, size_t count, uint32_t cols, uint32_t rows, int per_cell) {
  std::vector<int> c(static_cast<size_t>(cols) * rows, 0);
  for (size_t i = 0; i < count; ++i) {
    const uint32_t x = static_cast<uint32_t>(p[i].x * cols), y = static_cast<uint32_t>(p[i].y * rows);
    ++c[static_cast<size_t>(y) * cols + x];
  }
  for (int v : c) {
    if (v != per_cell) return false;
  }
  return true;
}

// Every power-of-two prefix of p is a (0,m,2)-net.
void ExpectNetsAtEveryPowerOfTwo(const PointSet& p) {
  for (int m = 0; (size_t{1} << m) <= p.size(); ++m) {
    for (int a = 0; a <= m; ++a) {
      ASSERT_TRUE(Stratified(p, size_t{1} << m, 1u << a, 1u << (m - a), 1))
          << "prefix 2^" << m << " shape " << a;
    }
  }
}

TEST(Pmj02, EveryPowerOfTwoPrefixIsANet) {
  for (int candidates : {1, kPmj02bnCandidates}) {
    for (uint64_t seed = 1; seed <= 6; ++seed) {
      auto p = Pmj02(4096, seed, candidates);
      ASSERT_TRUE(p.ok()) << p.status().message();
      ExpectNetsAtEveryPowerOfTwo(*p);
    }
  }
  auto big = Pmj02(1u << 16, 77, 1);
  ASSERT_TRUE(big.ok());
  ExpectNetsAtEveryPowerOfTwo(*big);
}

TEST(Pmj02, ProgressivePrefixesStayStratified) {
  auto p = Pmj02(4096, 3, kPmj02bnCandidates);
  ASSERT_TRUE(p.ok());
  for (int k = 0; (size_t{4} << (2 * k)) <= p->size(); ++k) {
    const uint32_t side = 1u << k;
    const size_t four_k = size_t{1} << (2 * k);
    // 4^k, 2 * 4^k, 3 * 4^k and 4 * 4^k points: 1, 2, 3, 4 per square stratum.
    for (int per = 1; per <= 4; ++per) {
      EXPECT_TRUE(Stratified(*p, per * four_k, side, side, per)) << "k=" << k << " per=" << per;
    }
    // 3 * 4^k points: at most one in each sub-quadrant.
    const size_t three = 3 * four_k;
    std::vector<int> c(4 * four_k, 0);
    for (size_t i = 0; i < three; ++i) {
      ++c[static_cast<size_t>((*p)[i].y * 2 * side) * 2 * side +
          static_cast<size_t>((*p)[i].x * 2 * side)];
    }
    for (int v : c) EXPECT_LE(v, 1) << "k=" << k;
  }
}

TEST(Pmj02, PrefixesOfLongerSequencesAreTheShorterSequences) {
  auto a = Pmj02(1000, 5, kPmj02bnCandidates), b = Pmj02(1024, 5, kPmj02bnCandidates);
  ASSERT_TRUE(a.ok() && b.ok());
  EXPECT_EQ(*a, PointSet(b->begin(), b->begin() + 1000));
}

TEST(Pmj02, RefusesBadArguments) {
  EXPECT_FALSE(Pmj02(0, 1, 1).ok());
  EXPECT_FALSE(Pmj02(16, 1, 0).ok());
  EXPECT_FALSE(Pmj02((1u << 20) + 1, 1, 1).ok());
}

}  // namespace
}  // namespace alignset

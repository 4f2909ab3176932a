#include "core/sampling/screen_space_rank1.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>

#include "core/sampling/periodic_blur.h"
#include "core/sampling/rank1_lattice.h"
#include "core/util/hash.h"

namespace alignset {
namespace {

TEST(PeriodicBlur, KernelIsNormalizedSymmetricAndIdentityAtZero) {
  for (double sigma : {0.5, 1.0, 2.0, 7.0}) {
    const std::vector<double> k = PeriodicGaussianKernel(sigma, 16);
    double sum = 0.0;
    for (double v : k) sum += v;
    EXPECT_NEAR(sum, 1.0, 1e-12) << sigma;
    for (int d = 1; d < 16; ++d) EXPECT_NEAR(k[d], k[16 - d], 1e-15) << sigma << " " << d;
  }
  const std::vector<double> id = PeriodicGaussianKernel(0.0, 8);
  EXPECT_EQ(id[0], 1.0);
  for (int d = 1; d < 8; ++d) EXPECT_EQ(id[d], 0.0);
}

TEST(PeriodicBlur, SquaredNormOfTheBlurIsTheAutocorrelationForm) {
  // ||k * e||^2 = sum_{p,q} e_p K(p - q) e_q with K the ring autocorrelation:
  // the identity the swap optimizer's O(T) update rests on.
  const int w = 12, h = 9;
  Pcg32 rng(3);
  std::vector<double> e(w * h);
  for (double& v : e) v = rng.NextDouble() - 0.5;
  for (double sigma : {0.7, 1.5, 4.0}) {
    const std::vector<double> b = PeriodicGaussianBlur(e, w, h, sigma);
    double norm = 0.0;
    for (double v : b) norm += v * v;
    const std::vector<double> kx = RingAutocorrelation(PeriodicGaussianKernel(sigma, w));
    const std::vector<double> ky = RingAutocorrelation(PeriodicGaussianKernel(sigma, h));
    double form = 0.0;
    for (int p = 0; p < w * h; ++p) {
      for (int q = 0; q < w * h; ++q) {
        const int dx = ((p % w) - (q % w) + w) % w, dy = ((p / w) - (q / w) + h) % h;
        form += e[p] * kx[dx] * ky[dy] * e[q];
      }
    }
    EXPECT_NEAR(norm, form, 1e-12 * std::max(1.0, norm)) << sigma;
  }
}

TEST(PeriodicBlur, MatchesADirectPeriodicSum) {
  const int w = 7, h = 5;
  std::vector<double> img(w * h, 0.0);
  img[2 * w + 3] = 1.0;  // an impulse: the blur is the kernel itself, wrapped
  const double sigma = 1.3;
  const std::vector<double> b = PeriodicGaussianBlur(img, w, h, sigma);
  const int r = static_cast<int>(std::ceil(3 * sigma));
  double norm = 0.0;
  for (int m = -r; m <= r; ++m) norm += std::exp(-0.5 * m * m / (sigma * sigma));
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      double want_x = 0.0, want_y = 0.0;
      for (int m = -r; m <= r; ++m) {
        if (((3 + m) % w + w) % w == x) want_x += std::exp(-0.5 * m * m / (sigma * sigma)) / norm;
        if (((2 + m) % h + h) % h == y) want_y += std::exp(-0.5 * m * m / (sigma * sigma)) / norm;
      }
      EXPECT_NEAR(b[y * w + x], want_x * want_y, 1e-14) << x << "," << y;
    }
  }
}

TEST(ScreenSpaceRank1, EachPixelIsItsShiftedLattice) {
  const uint32_t n = 64;
  const ShiftTile tile = RandomShiftTile(4, 9);
  const ScreenSpaceRank1 s(n, tile);
  EXPECT_EQ(s.generator(), Rank1Generator(n));
  for (int y = -1; y < 6; ++y) {
    for (int x = -2; x < 5; ++x) {
      const PointSet p = s.PixelSet(x, y);
      ASSERT_EQ(p.size(), n);
      const Point2 sh = tile.At(x, y);
      EXPECT_EQ(sh, tile.shifts[((y % 4 + 4) % 4) * 4 + (x % 4 + 4) % 4]);
      std::set<uint32_t> cols, rows;
      for (uint32_t k = 0; k < n; ++k) {
        const double ex = std::fmod(double(k) / n + sh.x, 1.0);
        const double ey = std::fmod(double((k * s.generator()) % n) / n + sh.y, 1.0);
        EXPECT_NEAR(p[k].x, ex, 1e-15);
        EXPECT_NEAR(p[k].y, ey, 1e-15);
        cols.insert(static_cast<uint32_t>(std::floor(std::fmod(p[k].x - sh.x + 1.0, 1.0) * n + 0.5)) % n);
        rows.insert(static_cast<uint32_t>(std::floor(std::fmod(p[k].y - sh.y + 1.0, 1.0) * n + 0.5)) % n);
      }
      EXPECT_EQ(cols.size(), n);  // a coprime generator: one point per column and row
      EXPECT_EQ(rows.size(), n);
    }
  }
}

TEST(ScreenSpaceRank1, SwapsKeepTheShiftsAndLowerTheBlurredError) {
  ShiftTileOptions o;
  o.size = 16;
  o.test_integrands = 48;
  o.sigma = 1.0;
  o.sweeps = 24;
  o.seed = 5;
  const uint32_t n = 16;
  ShiftTileReport report;
  auto tile = OptimizeShiftTile(n, o, &report);
  ASSERT_TRUE(tile.ok()) << tile.status().message();
  // Only swaps: the multiset of shifts is the random start's.
  std::vector<std::pair<double, double>> a, b;
  for (const Point2& p : tile->shifts) a.push_back({p.x, p.y});
  for (const Point2& p : RandomShiftTile(o.size, o.seed).shifts) b.push_back({p.x, p.y});
  std::sort(a.begin(), a.end());
  std::sort(b.begin(), b.end());
  EXPECT_EQ(a, b);
  EXPECT_GT(report.accepted, 0u);
  EXPECT_LT(report.loss_after, 0.6 * report.loss_before);

  // The incrementally kept loss equals the loss recomputed from scratch.
  double recomputed = 0.0;
  for (const std::vector<double>& e : TileErrorMaps(n, *tile, o.test_integrands, o.seed)) {
    for (double v : PeriodicGaussianBlur(e, o.size, o.size, o.sigma)) recomputed += v * v;
  }
  recomputed /= o.size * o.size;
  EXPECT_NEAR(report.loss_after, recomputed, 1e-9 * recomputed);

  // It generalizes: on fresh test integrands the blurred error is lower than
  // with the random (CP-per-pixel) assignment of the same shifts, while the
  // unblurred per-pixel error is the same multiset of lattice rules.
  const ShiftTile random = RandomShiftTile(o.size, o.seed);
  const double opt1 = TileBlurCriterion(n, *tile, 1.0, 64, 77);
  const double rnd1 = TileBlurCriterion(n, random, 1.0, 64, 77);
  EXPECT_LT(opt1, 0.8 * rnd1) << opt1 << " vs " << rnd1;
  const double opt0 = TileBlurCriterion(n, *tile, 0.0, 64, 77);
  const double rnd0 = TileBlurCriterion(n, random, 0.0, 64, 77);
  EXPECT_NEAR(opt0, rnd0, 0.05 * rnd0);
}

TEST(ScreenSpaceRank1, RefusesBadOptions) {
  ShiftTileOptions o;
  EXPECT_FALSE(OptimizeShiftTile(0, o).ok());
  o.size = 1;
  EXPECT_FALSE(OptimizeShiftTile(16, o).ok());
  o.size = 8;
  o.test_integrands = 0;
  EXPECT_FALSE(OptimizeShiftTile(16, o).ok());
}

TEST(ScreenSpaceRank1, SmallTilesWiderThanTheBlurStayExact) {
  // A blur wider than the tile wraps onto itself; the kept loss must still
  // equal the recomputed one.
  ShiftTileOptions o;
  o.size = 4;
  o.test_integrands = 16;
  o.sigma = 2.0;
  o.sweeps = 8;
  ShiftTileReport report;
  auto tile = OptimizeShiftTile(8, o, &report);
  ASSERT_TRUE(tile.ok());
  double recomputed = 0.0;
  for (const std::vector<double>& e : TileErrorMaps(8, *tile, o.test_integrands, o.seed)) {
    for (double v : PeriodicGaussianBlur(e, o.size, o.size, o.sigma)) recomputed += v * v;
  }
  recomputed /= o.size * o.size;
  EXPECT_NEAR(report.loss_after, recomputed, 1e-9 * std::max(recomputed, 1e-12));
}

}  // namespace
}  // namespace alignset

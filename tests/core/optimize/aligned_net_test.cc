// The aligned net (core/optimize/aligned_net.h): a net at every power of two
// by construction, better than Owen-Sobol on its edge without giving up the
// smooth integrands, deterministic, and strict about its input.
#include "core/optimize/aligned_net.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>

#include "core/sampling/owen_sobol.h"
#include "core/util/angles.h"
#include "core/util/hash.h"
#include "tests/net_intervals.h"

namespace alignset {
namespace {

TEST(AlignedNet, EveryPowerOfTwoPrefixIsANet) {
  for (const std::vector<double>& dirs : {std::vector<double>{30.0}, std::vector<double>{10.0},
                                          std::vector<double>{37.0, 118.0}}) {
    auto net = AlignedNet(256, dirs, 1);
    ASSERT_TRUE(net.ok()) << net.status().message();
    EXPECT_GT(net->flips, 0);
    EXPECT_LT(net->objective, net->start_objective);
    EXPECT_EQ(testing::PrefixNetViolation(net->points), "") << "theta " << dirs[0];
  }
}

// The Cranley-Patterson variance of f over `shifts` random shifts.
double CpVariance(const PointSet& p, const std::function<double(double, double)>& f, int shifts) {
  Pcg32 rng(4242);
  std::vector<double> e;
  for (int s = 0; s < shifts; ++s) {
    const double u = rng.NextDouble(), v = rng.NextDouble();
    double sum = 0.0;
    for (const Point2& q : p) {
      double x = q.x + u, y = q.y + v;
      x -= std::floor(x), y -= std::floor(y);
      sum += f(x, y);
    }
    e.push_back(sum / p.size());
  }
  double mean = 0.0, var = 0.0;
  for (double x : e) mean += x / e.size();
  for (double x : e) var += (x - mean) * (x - mean) / (e.size() - 1);
  return var;
}

TEST(AlignedNet, BeatsOwenSobolOnItsEdgeAndNotWorseOnSmoothFunctions) {
  constexpr uint32_t kN = 256;
  constexpr int kShifts = 2048, kScrambles = 16;
  const Vec2 n = UnitVector(30.0);
  auto edge = [n](double x, double y) { return (x - 0.5) * n.x + (y - 0.5) * n.y >= 0.0 ? 1.0 : 0.0; };
  auto gaussian = [](double x, double y) {
    return std::exp(-((x - 0.5) * (x - 0.5) + (y - 0.5) * (y - 0.5)) / (2 * 0.15 * 0.15));
  };
  auto product = [](double x, double y) { return x * y * std::exp(x * y); };  // not periodic
  auto net = AlignedNet(kN, {30.0}, 1);
  ASSERT_TRUE(net.ok());
  double os_edge = 0.0, os_gauss = 0.0, os_product = 0.0;
  for (int s = 1; s <= kScrambles; ++s) {
    const PointSet o = OwenScrambledSobol(kN, s);
    os_edge += CpVariance(o, edge, kShifts) / kScrambles;
    os_gauss += CpVariance(o, gaussian, kShifts) / kScrambles;
    os_product += CpVariance(o, product, kShifts) / kScrambles;
  }
  const double net_edge = CpVariance(net->points, edge, kShifts);
  EXPECT_LT(net_edge, 0.6 * os_edge);  // measured about 0.3
  EXPECT_LT(CpVariance(net->points, gaussian, kShifts), os_gauss);
  EXPECT_LT(CpVariance(net->points, product, kShifts), os_product);
}

TEST(AlignedNet, DeterministicAndSeedsDiffer) {
  auto a = AlignedNet(64, {45.0}, 3), b = AlignedNet(64, {45.0}, 3), c = AlignedNet(64, {45.0}, 4);
  ASSERT_TRUE(a.ok() && b.ok() && c.ok());
  bool same = true, differ = false;
  for (size_t i = 0; i < a->points.size(); ++i) {
    same &= a->points[i].x == b->points[i].x && a->points[i].y == b->points[i].y;
    differ |= a->points[i].x != c->points[i].x || a->points[i].y != c->points[i].y;
  }
  EXPECT_TRUE(same);
  EXPECT_TRUE(differ);
}

TEST(AlignedNet, RefusesBadInput) {
  EXPECT_FALSE(AlignedNet(100, {30.0}, 1).ok());  // not a power of two
  EXPECT_FALSE(AlignedNet(8, {30.0}, 1).ok());
  EXPECT_FALSE(AlignedNet(1u << 17, {30.0}, 1).ok());
  EXPECT_FALSE(AlignedNet(256, {std::nan("")}, 1).ok());
  EXPECT_FALSE(AlignedNet(256, {}, 1).ok());
  EXPECT_FALSE(AlignedNet(256, std::vector<double>(9, 10.0), 1).ok());
  AlignedNetOptions o;
  o.window_deg = -1.0;
  EXPECT_FALSE(AlignedNet(256, {30.0}, 1, o).ok());
  o = {};
  o.smooth_weight = std::nan("");
  EXPECT_FALSE(AlignedNet(256, {30.0}, 1, o).ok());
}

}  // namespace
}  // namespace alignset

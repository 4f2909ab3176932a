#include "core/align/canonical.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <utility>
#include <vector>

#include "core/spectral/direct_engine.h"
#include "core/spectral/frequency_set.h"
#include "core/util/hash.h"
#include "core/optimize/optimizer.h"
#include "tests/unit_square.h"

namespace alignset {
namespace {

std::vector<AlignOps> AllElements() {
  std::vector<AlignOps> all;
  for (int m = 0; m < 8; ++m) all.push_back({(m & 1) != 0, (m & 2) != 0, (m & 4) != 0});
  return all;
}

std::multiset<int> MappedKey(const Canonicalization& c) {
  std::multiset<int> out;
  out.insert(static_cast<int>(MapDirection(c.key.phi1, c.ops)));
  if (c.key.count == 2) out.insert(static_cast<int>(MapDirection(c.key.phi2, c.ops)));
  return out;
}

TEST(CanonicalKeys, CountsAre46And4141) {
  EXPECT_EQ(CanonicalKeyCount(1), 46u);
  EXPECT_EQ(CanonicalKeyCount(2), 4141u);
  EXPECT_EQ(CanonicalKeyCount(0), 0u);
  EXPECT_EQ(CanonicalKeyCount(3), 0u);
}

TEST(CanonicalKeys, IndexRoundTripsAndOrderIsAscending) {
  for (int count : {1, 2}) {
    CanonicalDirections prev{};
    for (size_t i = 0; i < CanonicalKeyCount(count); ++i) {
      const CanonicalDirections key = CanonicalKeyAt(count, i);
      EXPECT_EQ(key.count, count);
      EXPECT_LE(key.phi1, key.phi2);
      if (count == 1) {
        EXPECT_EQ(key.phi1, key.phi2);
      }
      auto index = CanonicalKeyIndex(key);
      ASSERT_TRUE(index.ok()) << ToString(key);
      EXPECT_EQ(*index, i);
      if (i > 0) {
        EXPECT_TRUE(std::make_pair(prev.phi1, prev.phi2) < std::make_pair(key.phi1, key.phi2))
            << "order contract broken at " << i;
      }
      prev = key;
    }
  }
  EXPECT_EQ(CanonicalKeyAt(1, 45), (CanonicalDirections{1, 45, 45}));
  EXPECT_EQ(CanonicalKeyAt(2, 0), (CanonicalDirections{2, 0, 0}));
}

TEST(CanonicalKeys, NonCanonicalKeysAreRefused) {
  EXPECT_FALSE(CanonicalKeyIndex({1, 46, 46}).ok());
  EXPECT_FALSE(CanonicalKeyIndex({1, 10, 11}).ok());
  EXPECT_FALSE(CanonicalKeyIndex({1, -1, -1}).ok());
  EXPECT_FALSE(CanonicalKeyIndex({3, 0, 0}).ok());
  // {90, 90} is in the orbit of {0, 0} (swap), which is its representative.
  EXPECT_FALSE(CanonicalKeyIndex({2, 90, 90}).ok());
  EXPECT_FALSE(CanonicalKeyIndex({2, 20, 10}).ok());
  EXPECT_FALSE(CanonicalKeyIndex({2, 0, 180}).ok());
}

TEST(Canonicalize, EverySingleDirectionMapsBack) {
  std::set<int> keys;
  for (int t = 0; t < 180; ++t) {
    auto c = Canonicalize({static_cast<double>(t)});
    ASSERT_TRUE(c.ok());
    EXPECT_EQ(c->key.count, 1);
    EXPECT_GE(c->key.phi1, 0);
    EXPECT_LE(c->key.phi1, 45);
    EXPECT_FALSE(c->ops.invert_y);
    EXPECT_EQ(c->served_deg, std::vector<int>{t});
    EXPECT_EQ(MapDirection(c->key.phi1, c->ops), static_cast<double>(t)) << t;
    keys.insert(c->key.phi1);
  }
  EXPECT_EQ(keys.size(), 46u);
}

TEST(Canonicalize, AlgorithmOneTable) {
  auto at = [](double t) { return *Canonicalize({t}); };
  EXPECT_EQ(at(30).key.phi1, 30);
  EXPECT_EQ(at(30).ops, (AlignOps{false, false, false}));
  EXPECT_EQ(at(45).ops, (AlignOps{false, false, false}));
  EXPECT_EQ(at(60).key.phi1, 30);
  EXPECT_EQ(at(60).ops, (AlignOps{true, false, false}));
  EXPECT_EQ(at(90).key.phi1, 0);
  EXPECT_EQ(at(90).ops, (AlignOps{true, false, false}));
  EXPECT_EQ(at(120).key.phi1, 30);
  EXPECT_EQ(at(120).ops, (AlignOps{true, true, false}));
  EXPECT_EQ(at(135).ops, (AlignOps{true, true, false}));
  EXPECT_EQ(at(150).key.phi1, 30);
  EXPECT_EQ(at(150).ops, (AlignOps{false, true, false}));
}

TEST(Canonicalize, EveryUnorderedPairMapsBack) {
  std::set<std::pair<int, int>> reached;
  size_t pairs = 0;
  for (int a = 0; a < 180; ++a) {
    for (int b = a; b < 180; ++b) {
      ++pairs;
      for (auto request : {std::vector<double>{double(a), double(b)},
                           std::vector<double>{double(b), double(a)}}) {
        auto c = Canonicalize(request);
        ASSERT_TRUE(c.ok());
        ASSERT_EQ(c->key.count, 2);
        ASSERT_TRUE(CanonicalKeyIndex(c->key).ok()) << ToString(c->key);
        EXPECT_FALSE(c->ops.invert_y);
        EXPECT_EQ(MappedKey(*c), (std::multiset<int>{a, b})) << a << "," << b;
        reached.insert({c->key.phi1, c->key.phi2});
      }
    }
  }
  EXPECT_EQ(pairs, 16290u);
  EXPECT_EQ(reached.size(), 4141u);
}

TEST(Canonicalize, KeyIsAnOrbitInvariant) {
  for (int a = 0; a < 180; a += 7) {
    for (int b = 0; b < 180; b += 11) {
      const CanonicalDirections key = Canonicalize({double(a), double(b)})->key;
      for (const AlignOps& g : AllElements()) {
        const double ga = MapDirection(a, g), gb = MapDirection(b, g);
        EXPECT_EQ(Canonicalize({ga, gb})->key, key);
      }
    }
  }
}

TEST(Canonicalize, AnyFiniteAngleReducedAndRounded) {
  auto served = [](double t) { return Canonicalize({t})->served_deg[0]; };
  EXPECT_EQ(served(179.6), 0);
  EXPECT_EQ(served(179.4), 179);
  EXPECT_EQ(served(-0.4), 0);
  EXPECT_EQ(served(-30), 150);
  EXPECT_EQ(served(210.2), 30);
  EXPECT_EQ(served(30.5), 31);
  EXPECT_EQ(served(1e12 + 30), static_cast<int>(std::fmod(1e12 + 30, 180.0)));
  EXPECT_EQ(served(-1e-300), 0);
  auto c = Canonicalize({-30.2, 400.0});
  ASSERT_TRUE(c.ok());
  EXPECT_EQ(c->requested_deg, (std::vector<double>{-30.2, 400.0}));
  EXPECT_EQ(c->served_deg, (std::vector<int>{150, 40}));
  EXPECT_EQ(MappedKey(*c), (std::multiset<int>{150, 40}));
}

TEST(Canonicalize, RefusesBadInput) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  for (const auto& bad : {std::vector<double>{}, std::vector<double>{1, 2, 3},
                          std::vector<double>{nan}, std::vector<double>{inf},
                          std::vector<double>{10, -inf}}) {
    auto c = Canonicalize(bad);
    ASSERT_FALSE(c.ok());
    EXPECT_EQ(c.status().code(), Status::Code::kInvalidArgument);
    EXPECT_FALSE(c.status().message().empty());
  }
}

// --- The group on points -------------------------------------------------

// Points on the 2^-53 grid, including the edges of [0,1).
PointSet GridPoints() {
  const double ulp_below_one = std::nextafter(1.0, 0.0);
  const std::vector<double> v = {0.0, 0x1.0p-53, 0x1.0p-52, 3 * 0x1.0p-53, 0.25, 0.5 - 0x1.0p-53,
                                 0.5, 0.5 + 0x1.0p-53, 0.75, ulp_below_one, 1.0 / 3.0 + 0.5};
  PointSet p;
  for (double x : v) {
    for (double y : v) p.push_back({x, y});
  }
  Pcg32 rng(99);
  for (int i = 0; i < 256; ++i) p.push_back({rng.NextDouble(), rng.NextDouble()});
  return p;
}

TEST(Align, GroupLawsHoldBitForBit) {
  const PointSet p = GridPoints();
  EXPECT_EQ(Align(p, {}), p);  // the identity on grid points
  for (const AlignOps& a : AllElements()) {
    const PointSet pa = Align(p, a);
    EXPECT_EQ(testing::OutsideUnitSquare(pa), "");
    EXPECT_EQ(Compose(a, Inverse(a)), AlignOps{});
    EXPECT_EQ(Compose(Inverse(a), a), AlignOps{});
    EXPECT_EQ(Align(pa, Inverse(a)), p) << ToString(a);
    for (const AlignOps& b : AllElements()) {
      EXPECT_EQ(Align(pa, b), Align(p, Compose(a, b))) << ToString(a) << " then " << ToString(b);
      for (int t = 0; t < 180; t += 5) {
        EXPECT_EQ(MapDirection(MapDirection(t, a), b), MapDirection(t, Compose(a, b)));
      }
    }
  }
  // The eight elements are distinct maps.
  std::set<std::vector<double>> images;
  for (const AlignOps& a : AllElements()) {
    const Point2 q = AlignPoint({0.125, 0.25}, a);
    images.insert({q.x, q.y});
  }
  EXPECT_EQ(images.size(), 8u);
}

TEST(Align, MatchesTheGeometricMaps) {
  const Point2 p{0.125, 0.25};
  EXPECT_EQ(AlignPoint(p, {true, false, false}), (Point2{0.25, 0.125}));
  EXPECT_EQ(AlignPoint(p, {false, true, false}), (Point2{0.875, 0.25}));
  EXPECT_EQ(AlignPoint(p, {true, true, false}), (Point2{0.75, 0.125}));
  EXPECT_EQ(AlignPoint(p, {false, false, true}), (Point2{0.125, 0.75}));
  // 0 is its own mirror image on the torus (1 - 0 = 1 wraps to 0).
  EXPECT_EQ(AlignPoint({0.0, 0.0}, {false, true, true}), (Point2{0.0, 0.0}));
  EXPECT_EQ(AlignPoint({0x1.0p-53, 0.5}, {false, true, true}),
            (Point2{std::nextafter(1.0, 0.0), 0.5}));
}

TEST(Align, OffGridValuesMoveByAtMostHalfAGridStep) {
  const double tiny[] = {1e-300, 5e-324, 0x1.0p-60, 0x1.0p-54, 0.25 + 0x1.0p-54,
                         0.5 - 0x1.0p-54, 0.1, -0.0, 1e-17};
  PointSet p;
  for (double x : tiny) p.push_back({x, 0.5});
  const PointSet q = Align(p, {});
  EXPECT_EQ(testing::OutsideUnitSquare(q), "");
  for (size_t i = 0; i < p.size(); ++i) EXPECT_LE(std::abs(q[i].x - p[i].x), 0x1.0p-54);
  // Once on the grid the group acts exactly, whatever the input was.
  for (const AlignOps& a : AllElements()) {
    EXPECT_EQ(Align(Align(p, a), Inverse(a)), q);
    EXPECT_EQ(testing::OutsideUnitSquare(Align(p, a)), "");
  }
  // Out-of-range inputs are wrapped rather than trusted.
  EXPECT_EQ(testing::OutsideUnitSquare(Align({{1.0, -0.25}, {-1e-17, 2.5}}, {true, true, false})), "");
}

// --- Integration: an optimized canonical set aligned to four quadrants ----

double MeanPeriodogram(const PointSet& p, const FrequencyParams& params, double deg,
                       DirectEngine* engine) {
  // Only the strip beyond the disk: the disk is dark in every direction.
  std::vector<Frequency> k;
  for (const Frequency& f : StripFrequencies(params, deg)) {
    if (std::hypot(f.a, f.b) > params.radius + 1.0) k.push_back(f);
  }
  engine->SetFrequencies(k);
  SpectrumEvaluation e;
  engine->Evaluate(p, false, &e);
  return e.loss;
}

TEST(AlignIntegration, OptimizedSetIsDarkAlongEveryRequestedDirection) {
  const int phi = 30;
  OptimizationProblem problem;
  problem.n = 256;
  problem.directions = {static_cast<double>(phi)};
  problem.seed = 3;
  // The flat loss darkens the whole strip, beyond the disk too, which is
  // what tells the four aligned directions apart here.
  OptimizerOptions options = SupplementOptimizerOptions();
  options.max_iterations = 300;
  DirectEngine engine(2);
  auto result = Optimize(problem, options, engine);
  ASSERT_TRUE(result.ok()) << result.status().message();
  const FrequencyParams params = result->frequency_params;

  // phi = 30 serves 30 (identity), 60 (swap), 120 (swap + invert) and 150
  // (invert); each aligned set must be dark along its own request and not
  // along the other three (which is where a wrong element would put it).
  const std::vector<int> requests = {30, 60, 120, 150};
  for (int t : requests) {
    auto c = Canonicalize({static_cast<double>(t)});
    ASSERT_TRUE(c.ok());
    ASSERT_EQ(c->key.phi1, phi);
    const PointSet aligned = Align(result->points, c->ops);
    EXPECT_EQ(testing::OutsideUnitSquare(aligned), "");
    const double dark = MeanPeriodogram(aligned, params, t, &engine);
    for (int other : requests) {
      if (other == t) continue;
      const double bright = MeanPeriodogram(aligned, params, other, &engine);
      EXPECT_LT(dark, 0.1 * bright) << "request " << t << " vs " << other << ": " << dark
                                     << " / " << bright;
    }
  }
}

TEST(AlignIntegration, QuarterDegreeSetIsDarkAlongEveryRequestedDirection) {
  // Algorithm 1 on the quarter-degree grid: phi = 10.25 serves 10.25, 79.75,
  // 100.25 and 169.75.
  OptimizationProblem problem;
  problem.n = 256;
  problem.directions = {10.25};
  problem.seed = 5;
  // As in the whole-degree test above: the flat loss darkens the whole strip,
  // which is what tells the four aligned directions apart.
  OptimizerOptions options = SupplementOptimizerOptions();
  options.max_iterations = 300;
  DirectEngine engine(2);
  auto result = Optimize(problem, options, engine);
  ASSERT_TRUE(result.ok()) << result.status().message();
  const FrequencyParams params = result->frequency_params;
  const std::vector<double> requests = {10.25, 79.75, 100.25, 169.75};
  for (double t : requests) {
    auto c = Canonicalize({t}, AngleGrid::kQuarterDegree);
    ASSERT_TRUE(c.ok());
    ASSERT_EQ(c->key, (CanonicalDirections{1, 10, 10, 1}));
    ASSERT_EQ(c->served_exact_deg, std::vector<double>{t});
    const PointSet aligned = Align(result->points, c->ops);
    EXPECT_EQ(testing::OutsideUnitSquare(aligned), "");
    const double dark = MeanPeriodogram(aligned, params, t, &engine);
    for (double other : requests) {
      if (other == t) continue;
      const double bright = MeanPeriodogram(aligned, params, other, &engine);
      EXPECT_LT(dark, 0.1 * bright) << "request " << t << " vs " << other;
    }
  }
}

TEST(QuarterGrid, CountsOrderAndWholeDegreeSubset) {
  EXPECT_EQ(CanonicalKeyCount(1, AngleGrid::kQuarterDegree), 181u);
  EXPECT_EQ(CanonicalKeyCount(2, AngleGrid::kQuarterDegree), 0u);
  EXPECT_EQ(CanonicalKeyCount(1, AngleGrid::kWholeDegree), 46u);
  EXPECT_EQ(CanonicalKeyCount(2, AngleGrid::kWholeDegree), 4141u);
  double prev = -1;
  for (size_t i = 0; i < 181; ++i) {
    const CanonicalDirections key = CanonicalKeyAt(1, i, AngleGrid::kQuarterDegree);
    EXPECT_EQ(Phi1Degrees(key), 0.25 * i);
    EXPECT_GT(Phi1Degrees(key), prev);
    prev = Phi1Degrees(key);
    auto index = CanonicalKeyIndex(key, AngleGrid::kQuarterDegree);
    ASSERT_TRUE(index.ok());
    EXPECT_EQ(*index, i);
    // Whole degrees are the old keys, unchanged, at index 4k.
    if (i % 4 == 0) {
      EXPECT_EQ(key, CanonicalKeyAt(1, i / 4));
      EXPECT_EQ(*CanonicalKeyIndex(key), i / 4);
    } else {
      EXPECT_FALSE(CanonicalKeyIndex(key).ok()) << "a quarter is not a whole-degree key";
    }
  }
  EXPECT_EQ(ToString(CanonicalKeyAt(1, 121, AngleGrid::kQuarterDegree)), "phi=30.25");
  EXPECT_EQ(ToString(CanonicalKeyAt(1, 120, AngleGrid::kQuarterDegree)), "phi=30");
  EXPECT_FALSE(CanonicalKeyIndex({1, 45, 45, 1}, AngleGrid::kQuarterDegree).ok());
  EXPECT_FALSE(CanonicalKeyIndex({1, 10, 10, 4}, AngleGrid::kQuarterDegree).ok());
  EXPECT_FALSE(CanonicalKeyIndex({2, 10, 20, 0}, AngleGrid::kQuarterDegree).ok());
}

TEST(QuarterGrid, EveryQuarterDirectionMapsBack) {
  std::set<int> keys;
  for (int q = 0; q < 720; ++q) {
    const double t = 0.25 * q;
    auto c = Canonicalize({t}, AngleGrid::kQuarterDegree);
    ASSERT_TRUE(c.ok());
    EXPECT_EQ(c->grid, AngleGrid::kQuarterDegree);
    ASSERT_TRUE(CanonicalKeyIndex(c->key, AngleGrid::kQuarterDegree).ok()) << t;
    EXPECT_EQ(c->served_exact_deg, std::vector<double>{t});
    EXPECT_EQ(MapDirection(Phi1Degrees(c->key), c->ops), t) << t;
    keys.insert(static_cast<int>(*CanonicalKeyIndex(c->key, AngleGrid::kQuarterDegree)));
    // On whole degrees both grids agree.
    if (q % 4 == 0) {
      auto whole = Canonicalize({t});
      EXPECT_EQ(whole->key, c->key);
      EXPECT_EQ(whole->ops, c->ops);
    }
  }
  EXPECT_EQ(keys.size(), 181u);
}

TEST(QuarterGrid, AlgorithmOneTableAndRounding) {
  auto at = [](double t) { return *Canonicalize({t}, AngleGrid::kQuarterDegree); };
  EXPECT_EQ(at(30.25).key, (CanonicalDirections{1, 30, 30, 1}));
  EXPECT_EQ(at(30.25).ops, (AlignOps{}));
  EXPECT_EQ(at(59.75).key, (CanonicalDirections{1, 30, 30, 1}));
  EXPECT_EQ(at(59.75).ops, (AlignOps{true, false, false}));
  EXPECT_EQ(at(120.25).ops, (AlignOps{true, true, false}));
  EXPECT_EQ(at(149.75).ops, (AlignOps{false, true, false}));
  EXPECT_EQ(at(45.0).key, (CanonicalDirections{1, 45, 45, 0}));
  EXPECT_EQ(at(45.25).key, (CanonicalDirections{1, 44, 44, 3}));  // (45, 90]: swap
  EXPECT_TRUE(at(45.25).ops.swap);
  EXPECT_EQ(at(90.25).key, (CanonicalDirections{1, 0, 0, 1}));
  EXPECT_EQ(at(135.25).key, (CanonicalDirections{1, 44, 44, 3}));
  // Nearest quarter, ties away from zero, reduced mod 180.
  EXPECT_EQ(at(30.1).served_exact_deg[0], 30.0);
  EXPECT_EQ(at(30.13).served_exact_deg[0], 30.25);
  EXPECT_EQ(at(30.125).served_exact_deg[0], 30.25);
  EXPECT_EQ(at(179.9).served_exact_deg[0], 0.0);
  EXPECT_EQ(at(-0.3).served_exact_deg[0], 179.75);
  EXPECT_EQ(at(400.6).served_exact_deg[0], 40.5);
  EXPECT_EQ(at(30.5).served_deg[0], 31);  // the integer field: nearest whole degree
  // Two directions stay on whole degrees.
  auto two = *Canonicalize({10.3, 100.6}, AngleGrid::kQuarterDegree);
  EXPECT_EQ(two.grid, AngleGrid::kWholeDegree);
  EXPECT_EQ(two.served_exact_deg, (std::vector<double>{10, 101}));
  EXPECT_EQ(two.key.phi1_quarter, 0);
}

}  // namespace
}  // namespace alignset

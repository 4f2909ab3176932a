// Every sampler of the renderer on a few pixels of both scenes at low N: each
// estimate, over independent replicates (render seeds), must agree with the
// exact reference within its own statistical bound. No golden images.
#include "render/pixel_samplers.h"

#include <gtest/gtest.h>

#include <cmath>

#include "render/direction.h"
#include "render/lattice_sets.h"
#include "render/renderer.h"
#include "render/scene.h"
#include "render/spectral_estimator.h"
#include "core/optimize/aligned_lattice.h"
#include "core/sampling/samplers.h"
#include "core/util/hash.h"

namespace alignset::render {
namespace {

struct Fixture {
  Scene scene;
  std::vector<PixelDirection> exact, estimated;
  std::vector<size_t> pixels;  // edge pixels (one- and two-direction) and smooth ones
};

const Fixture& Get(const std::string& name) {
  static std::map<std::string, Fixture> cache;
  auto it = cache.find(name);
  if (it != cache.end()) return it->second;
  Fixture f;
  f.scene = *MakeScene(name, 128, 128, 1);
  f.exact = GeometryDirections(f.scene);
  const std::vector<PixelClass> classes = f.scene.Classes();
  int one = 0, two = 0, smooth = 0;
  for (size_t k = 0; k < classes.size(); ++k) {
    const size_t i = (k * 7919 + 101) % classes.size();  // spread over the image
    if (classes[i] == PixelClass::kEdge && f.exact[i].kind == PixelDirection::Kind::kOne && one < 3) {
      f.pixels.push_back(i), ++one;
    } else if (classes[i] == PixelClass::kEdge && f.exact[i].kind == PixelDirection::Kind::kTwo &&
               two < 2) {
      f.pixels.push_back(i), ++two;
    } else if (classes[i] == PixelClass::kSmooth && smooth < 2) {
      f.pixels.push_back(i), ++smooth;
    }
  }
  // The estimator of record on the chosen pixels only (the whole image
  // would cost seconds), seeded as EstimateDirections seeds them.
  const auto estimator = MakeSpectralEstimator(*ParsePrepass(kDefaultPrepass));
  f.estimated.assign(f.scene.size(), PixelDirection{});
  for (size_t i : f.pixels) f.estimated[i] = estimator->Estimate(f.scene.Pixel(i), HashCombine(1, i));
  return cache.emplace(name, std::move(f)).first->second;
}

struct Stats {
  double mean = 0.0, sd = 0.0;
};
Stats Replicates(const Scene& s, const PixelSampler& sampler, size_t i, int reps) {
  std::vector<double> e;
  for (int r = 1; r <= reps; ++r) {
    e.push_back(RenderPixel(s, sampler, static_cast<int>(i % s.width()),
                            static_cast<int>(i / s.width()), static_cast<uint64_t>(r)));
  }
  Stats st;
  for (double v : e) st.mean += v / reps;
  for (double v : e) st.sd += (v - st.mean) * (v - st.mean);
  st.sd = std::sqrt(st.sd / (reps - 1));
  return st;
}

std::vector<SamplerConfig> AllConfigs(const Fixture& f, uint32_t n, const ShiftTile* tile) {
  std::vector<SamplerConfig> out;
  for (const std::string& name : SamplerNames()) out.push_back({name, n});
  for (const char* name : {"pmj02bn-sheared", "pmj02bn-sheared-exact", "screen-space-rank1"}) {
    out.push_back({name, n});
  }
  for (const char* name : {"line", "segment"}) {
    for (LineOrientation o : {LineOrientation::kNormal, LineOrientation::kEdge, LineOrientation::kRandom}) {
      SamplerConfig c{name, n};
      c.orientation = o;
      out.push_back(c);
    }
  }
  for (SamplerConfig& c : out) {
    c.estimated = &f.estimated;
    c.exact = &f.exact;
    c.tile = tile;
  }
  return out;
}

TEST(RenderSamplers, EveryEstimateAgreesWithTheExactPixelWithinItsBound) {
  constexpr int kReps = 24;
  for (uint32_t n : {16u, 64u}) {
    ShiftTileOptions o;
    o.size = 16;
    o.test_integrands = 32;
    o.sweeps = 8;
    const ShiftTile tile = *OptimizeShiftTile(n, o);
    for (const char* scene : {"antialias", "shadow"}) {
      const Fixture& f = Get(scene);
      ASSERT_GE(f.pixels.size(), 6u) << scene;
      for (const SamplerConfig& c : AllConfigs(f, n, &tile)) {
        auto sampler = MakePixelSampler(c);
        ASSERT_TRUE(sampler.ok()) << c.name << ": " << sampler.status().message();
        for (size_t i : f.pixels) {
          const PixelIntegrand& px = f.scene.Pixel(i);
          const Stats st = Replicates(f.scene, **sampler, i, kReps);
          ASSERT_TRUE(std::isfinite(st.mean)) << c.name;
          // The replicates' spread is the estimator's own error scale: the
          // mean of 24 must sit within 5 standard errors (Student t, 23
          // degrees of freedom: a false alarm about once in 30000 checks).
          EXPECT_NEAR(st.mean, px.Exact(), 5.0 * st.sd / std::sqrt(double(kReps)) + 1e-12)
              << scene << " " << c.name << " orientation " << int(c.orientation) << " N=" << n
              << " pixel " << i << " class " << int(px.Classify());
          if (px.Classify() == PixelClass::kEdge) {
            // A real randomization: replicates differ where the integrand
            // has an edge (else the bound above would prove nothing).
            EXPECT_GT(st.sd, 0.0) << scene << " " << c.name << " pixel " << i;
          }
        }
      }
    }
  }
}

TEST(RenderSamplers, LineSamplesConvergeAtTheSeedsRates) {
  // Singh, Miller and Jarosz: jittered lines across a step pre-filter it to a C0 function of
  // the offset (variance ~ N^-3); lines along it keep the jump (~ N^-2).
  // Averaged over 48 straight edges at random angles and offsets (a single
  // edge's variance along it swings with where the jump falls in its stratum).
  Pcg32 rng(17);
  std::vector<std::pair<PixelIntegrand, double>> pixels;
  for (int k = 0; k < 48; ++k) {
    const double deg = 180.0 * rng.NextDouble(), rad = deg * M_PI / 180.0;
    const V2 nn = {std::cos(rad), std::sin(rad)};
    const V2 c = {0.3 + 0.4 * rng.NextDouble(), 0.3 + 0.4 * rng.NextDouble()};
    const Polygon half = ClipHalfPlane({{0, 0}, {1, 0}, {1, 1}, {0, 1}}, nn, Dot(nn, c));
    pixels.push_back({PixelIntegrand(Linear{0.2, 0, 0}, {Fragment{half, Linear{0.9, 0, 0}, {}}}), deg});
  }
  auto variance = [&](bool across, uint32_t n) {
    double v = 0.0;
    for (const auto& [f, deg] : pixels) {
      for (int r = 0; r < 48; ++r) {
        const double e = LineEstimate(f, n, across ? deg : deg + 90.0, 1000 + r) - f.Exact();
        v += e * e;
      }
    }
    return v / (48.0 * pixels.size());
  };
  const double slope_across = std::log(variance(true, 64) / variance(true, 16)) / std::log(4.0);
  const double slope_along = std::log(variance(false, 64) / variance(false, 16)) / std::log(4.0);
  EXPECT_LT(slope_across, -2.6);
  EXPECT_GT(slope_along, -2.4);
  EXPECT_LT(slope_along, -1.6);
  EXPECT_LT(variance(true, 64), 0.2 * variance(false, 64));
}

TEST(RenderSamplers, RefusesWhatItCannotDo) {
  EXPECT_FALSE(MakePixelSampler({"no-such-sampler", 16}).ok());
  EXPECT_FALSE(MakePixelSampler({"jittered", 15}).ok());  // square N only
  EXPECT_FALSE(MakePixelSampler({"aligned", 16}).ok());   // no sets, no directions
  EXPECT_FALSE(MakePixelSampler({"aligned-lattice", 16}).ok());
  const std::vector<PixelDirection> none(4);
  SamplerConfig lattice{"aligned-lattice-exact", 64};
  lattice.exact = &none;  // directions, but no lattice table
  EXPECT_FALSE(MakePixelSampler(lattice).ok());
  EXPECT_FALSE(AlignedLatticeTable(8, {&none}, AlignedPolicy{}, 1.0, 1).ok());  // N < 16, even unused
  EXPECT_TRUE(AlignedLatticeTable(64, {&none}, AlignedPolicy{}, 1.0, 1).ok());
  std::vector<PixelDirection> one(1);
  one[0].kind = PixelDirection::Kind::kOne;
  one[0].theta1 = 30.0;
  EXPECT_FALSE(AlignedLatticeTable(8, {&one}, AlignedPolicy{}, 1.0, 1).ok());    // N < 16
  EXPECT_FALSE(AlignedLatticeTable(256, {&one}, AlignedPolicy{}, 11.0, 1).ok());  // window > 10°
  EXPECT_FALSE(MakePixelSampler({"screen-space-rank1", 16}).ok());
  SamplerConfig seg{"segment", 16};
  seg.orientation = LineOrientation::kRandom;
  seg.segment_length = 0.0;
  EXPECT_FALSE(MakePixelSampler(seg).ok());
}

// With a size span each key gets the lattice size in [N - span, N] whose
// chosen generator scores best for its directions (render/lattice_sets.h):
// every served set is a rank-1 lattice of such a size, its score is the
// least over the sizes, and the sampler over it stays unbiased.
TEST(RenderSamplers, ALatticeTableWithASizeSpanGivesEachKeyItsBestScoringSize) {
  constexpr uint32_t kN = 128, kSpan = 6;
  std::vector<PixelDirection> dirs;
  for (double theta : {10.0, 30.0, 63.0, 97.0, 151.0}) {
    PixelDirection d;
    d.kind = PixelDirection::Kind::kOne;
    d.theta1 = theta;
    dirs.push_back(d);
  }
  PixelDirection pair;
  pair.kind = PixelDirection::Kind::kTwo;
  pair.theta1 = 20.0;
  pair.theta2 = 75.0;
  dirs.push_back(pair);
  LatticeTableStats st;
  auto table = AlignedLatticeTable(kN, {&dirs}, AlignedPolicy{}, 1.0, 1, &st, {}, false, kSpan);
  ASSERT_TRUE(table.ok()) << table.status().message();
  EXPECT_EQ(st.searched % (kSpan + 1), 0u);
  const SetTable::Sections sections = table->table->Resolve(kN, table->construction);
  auto check = [&](const SetChoice& c, const std::vector<double>& served) {
    auto set = table->table->Find(sections, c);
    ASSERT_TRUE(set.ok()) << set.status().message();
    const uint32_t size = set->n;
    ASSERT_GE(size, kN - kSpan);
    ASSERT_LE(size, kN);
    const uint32_t g = set->lattice_generator;
    ASSERT_NE(g, 0u) << "not a lattice";
    auto score = AlignedLatticeScore(size, g, served);
    ASSERT_TRUE(score.ok());
    for (uint32_t other = kN - kSpan; other <= kN; ++other) {
      auto best = ChooseAlignedLatticeGenerator(other, served);
      ASSERT_TRUE(best.ok());
      EXPECT_LE(*score, best->score + 1e-9 * std::fabs(best->score))
          << "served " << served[0] << " with " << size << " points; " << other << " scores better";
    }
  };
  for (int a : {10, 30, 63, 97, 151}) check({SetChoice::Kind::kOne, a, 0}, {static_cast<double>(a)});
  check({SetChoice::Kind::kTwo, 20, 75}, {20.0, 75.0});
  EXPECT_GT(st.smaller, 0u);  // at these keys some size below N wins
  // The sampler reads sets of any size: unbiased on a pixel's edge.
  const Fixture& f = Get("shadow");
  auto spanned = AlignedLatticeTable(kN, {&f.exact}, AlignedPolicy{}, 1.0, 1, nullptr, {}, false, kSpan);
  ASSERT_TRUE(spanned.ok());
  SamplerConfig c{"aligned-lattice-exact", kN};
  c.exact = &f.exact;
  c.sets = &*spanned;
  auto sampler = MakePixelSampler(c);
  ASSERT_TRUE(sampler.ok()) << sampler.status().message();
  int edges = 0;
  for (size_t i : f.pixels) {
    const PixelIntegrand& px = f.scene.Pixel(i);
    if (px.Classify() != PixelClass::kEdge || edges >= 6) continue;
    ++edges;
    const Stats s = Replicates(f.scene, **sampler, i, 24);
    EXPECT_NEAR(s.mean, px.Exact(), 5.0 * s.sd / std::sqrt(24.0) + 1e-12) << "pixel " << i;
  }
  EXPECT_GT(edges, 0);
  // A span that leaves fewer than 16 points is refused.
  EXPECT_FALSE(AlignedLatticeTable(32, {&dirs}, AlignedPolicy{}, 1.0, 1, nullptr, {}, false, 17).ok());
  EXPECT_TRUE(AlignedLatticeTable(32, {&dirs}, AlignedPolicy{}, 1.0, 1, nullptr, {}, false, 16).ok());
}

// The plain lattices and the tent-folded ones (whose pixels shift before
// the fold).
TEST(RenderSamplers, AlignedLatticesAreUnbiasedAndBeatOwenSobolOnStraightEdges) {
  constexpr int kReps = 24;
  constexpr uint32_t kN = 256;
  for (const bool folded : {false, true}) {
  for (const char* scene : {"antialias", "shadow"}) {
    const Fixture& f = Get(scene);
    LatticeTableStats st;
    auto table = AlignedLatticeTable(kN, {&f.exact, &f.estimated}, AlignedPolicy{}, folded ? 2.0 : 1.0, 1, &st,
                                     {}, folded);
    ASSERT_TRUE(table.ok()) << table.status().message();
    EXPECT_GT(st.one, 0u) << scene;
    EXPECT_EQ(table->construction, folded ? "tent-lattice" : "lattice");
    double lattice_mse = 0.0, sobol_mse = 0.0;
    const std::string plain = folded ? "aligned-tent-lattice" : "aligned-lattice";
    // A table of the other kind is refused.
    SamplerConfig other{folded ? "aligned-lattice" : "aligned-tent-lattice", kN};
    other.estimated = &f.estimated;
    other.sets = &*table;
    EXPECT_FALSE(MakePixelSampler(other).ok()) << plain;
    for (const std::string& name : {plain, plain + "-exact"}) {
      SamplerConfig c{name, kN};
      c.estimated = &f.estimated;
      c.exact = &f.exact;
      c.sets = &*table;
      auto sampler = MakePixelSampler(c);
      ASSERT_TRUE(sampler.ok()) << sampler.status().message();
      auto sobol = MakePixelSampler({"owen-sobol", kN});
      for (size_t i : f.pixels) {
        const PixelIntegrand& px = f.scene.Pixel(i);
        const Stats st = Replicates(f.scene, **sampler, i, kReps);
        ASSERT_TRUE(std::isfinite(st.mean)) << name << " pixel " << i;  // every key was built
        EXPECT_NEAR(st.mean, px.Exact(), 5.0 * st.sd / std::sqrt(double(kReps)) + 1e-12)
            << scene << " " << name << " pixel " << i;
        if (name == plain + "-exact" && px.Classify() == PixelClass::kEdge &&
            f.exact[i].kind == PixelDirection::Kind::kOne) {
          const Stats so = Replicates(f.scene, **sobol, i, kReps);
          lattice_mse += st.sd * st.sd;
          sobol_mse += so.sd * so.sd;
        }
      }
    }
    // A lattice chosen for the edge's normal integrates it with a fraction
    // of Owen-Sobol's variance (about 1/8 on a clean edge at N = 256, a
    // folded one about 1/3); 1/2 leaves room for the pixels' shading and
    // curvature.
    EXPECT_LT(lattice_mse, 0.5 * sobol_mse) << scene << " " << plain;
  }
  }
}

TEST(RenderSamplers, ImageErrorsSplitEdgeAndSmoothPixels) {
  const std::vector<double> ref = {0, 0, 0, 0};
  const std::vector<double> img = {1, 2, 3, 4};
  const std::vector<PixelClass> cls = {PixelClass::kEdge, PixelClass::kSmooth, PixelClass::kEdge,
                                       PixelClass::kConstant};
  const ImageErrors e = MeasureErrors(img, ref, cls, 2, 2, {0.0});
  EXPECT_DOUBLE_EQ(e.mse_edge, (1 + 9) / 2.0);
  EXPECT_DOUBLE_EQ(e.mse_smooth, 4.0);
  EXPECT_DOUBLE_EQ(e.mse_all, 30.0 / 4);
  EXPECT_EQ(e.edge_pixels, 2u);
  EXPECT_DOUBLE_EQ(e.blur_rms[0], std::sqrt(30.0 / 4));
}

}  // namespace
}  // namespace alignset::render

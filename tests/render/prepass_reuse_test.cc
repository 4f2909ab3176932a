// The pre-pass folded into a pixel's estimate (render/prepass_reuse.h): with
// the count weights the sum stays unbiased when the pre-pass is re-drawn with
// every replicate (its direction, hence the set chosen, and its mean change
// together); continuing the pre-pass's sequence on direction-less pixels
// makes them Owen-Sobol at N + P, at a selection bias measured small on the
// pixels whose branch changes between draws. The lattice pre-pass
// (render/prepass_lattice.h) is held to the same.
#include "render/prepass_reuse.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "render/lattice_sets.h"
#include "render/prepass_lattice.h"
#include "render/renderer.h"
#include "render/scene.h"
#include "render/spectral_estimator.h"
#include "core/sampling/owen_sobol.h"
#include "core/sampling/rank1_lattice.h"
#include "core/util/hash.h"

namespace alignset::render {
namespace {

TEST(PrepassReuse, TheWeightDependsOnTheCountsAlone) {
  EXPECT_DOUBLE_EQ(PrepassWeight(256, 256), 1.0 / 3.0);
  EXPECT_DOUBLE_EQ(PrepassWeight(0, 256), 0.0);
  EXPECT_NEAR(PrepassWeight(256, 4096), 1.0 / 129.0, 1e-12);
  EXPECT_GT(PrepassWeight(256, 1024), PrepassWeight(256, 4096));
  PixelDirection d;
  EXPECT_DOUBLE_EQ(WithPrepass(d, 0.3, 256), 0.3);  // nothing to reuse
  d.prepass_mean = 0.9;
  d.prepass_samples = 256;
  EXPECT_DOUBLE_EQ(WithPrepass(d, 0.3, 256), 0.5);
}

TEST(PrepassReuse, TheOwenSobolPrepassHandsOnItsMeanAndTheGridsDoNot) {
  const Scene scene = *MakeScene("shadow", 32, 32, 2);
  const PixelIntegrand& f = scene.Pixel(scene.size() / 2 + 7);
  for (const char* spec : {"samples256", "samples256c90", "jgrid16", "grid16c50"}) {
    const Prepass p = *ParsePrepass(spec);
    const PixelDirection d = MakeSpectralEstimator(p)->Estimate(f, 99);
    if (p.kind != Prepass::Kind::kSamples) {
      EXPECT_FALSE(p.Reusable()) << spec;
      EXPECT_EQ(d.prepass_samples, 0u) << spec;
    } else {
      // The mean survives the confidence floor (c90 makes the pixel
      // direction-less) and is the mean of the pre-pass's own points.
      EXPECT_TRUE(p.Reusable()) << spec;
      EXPECT_EQ(d.prepass_samples, 256u) << spec;
      double mean = 0.0;
      for (const Point2& q : OwenScrambledSobol(256, 99)) mean += f.Eval({q.x, q.y}) / 256.0;
      EXPECT_DOUBLE_EQ(d.prepass_mean, mean) << spec;
    }
  }
}

// aligned-lattice over a table with no sets, so every pixel of `dirs` is
// direction-less and takes the sampler's Owen-Sobol branch; the pre-pass
// reused (count weights) or not, continued or not.
std::unique_ptr<PixelSampler> DirectionLessLatticeSampler(const std::vector<PixelDirection>& dirs,
                                                         const RenderSets& empty, bool reuse,
                                                         bool continued) {
  SamplerConfig c{"aligned-lattice", empty.n};
  c.estimated = &dirs;
  c.sets = &empty;
  c.reuse_prepass = reuse;
  c.continue_prepass = continued;
  auto s = MakePixelSampler(c);
  EXPECT_TRUE(s.ok()) << s.status().message();
  return s.ok() ? std::move(*s) : nullptr;
}

TEST(PrepassLattice, ThePrepassIsAShiftedRankOneLatticeWhoseMeanIsHandedOn) {
  for (uint32_t m : {16u, 64u, 256u}) {
    const uint32_t g = Rank1Generator(m);
    for (uint64_t seed : {1ull, 77ull}) {
      const PointSet p = PrepassLatticePoints(m, seed);
      ASSERT_EQ(p.size(), m);
      // Point j is point 0 moved by j (1, g) / m on the torus.
      for (uint32_t j = 0; j < m; ++j) {
        auto torus = [](double d) { return d - std::floor(d + 0.5); };
        EXPECT_NEAR(torus(p[j].x - p[0].x - double(j) / m), 0.0, 1e-12) << m << " " << j;
        EXPECT_NEAR(torus(p[j].y - p[0].y - double(uint64_t(j) * g % m) / m), 0.0, 1e-12) << m << " " << j;
        EXPECT_TRUE(p[j].x >= 0.0 && p[j].x < 1.0 && p[j].y >= 0.0 && p[j].y < 1.0);
      }
      // One point in each of the m columns and rows (g is coprime to m).
      for (bool x : {true, false}) {
        std::vector<int> hits(m, 0);
        for (const Point2& q : p) ++hits[static_cast<size_t>((x ? q.x : q.y) * m)];
        EXPECT_EQ(*std::min_element(hits.begin(), hits.end()), 1) << m;
      }
    }
    EXPECT_NE(PrepassLatticePoints(m, 1)[0], PrepassLatticePoints(m, 2)[0]);  // a shift per pixel
  }
  // The estimator samples those points and hands on their mean, marked.
  const Scene scene = *MakeScene("shadow", 32, 32, 2);
  const PixelIntegrand& f = scene.Pixel(scene.size() / 2 + 7);
  for (const char* spec : {"edges64l", "samples64l", "nedges64s2l"}) {
    const PixelDirection d = MakeSpectralEstimator(*ParsePrepass(spec))->Estimate(f, 99);
    EXPECT_TRUE(d.prepass_lattice) << spec;
    EXPECT_EQ(d.prepass_samples, 64u) << spec;
    double mean = 0.0;
    for (const Point2& q : PrepassLatticePoints(64, 99)) mean += f.Eval({q.x, q.y}) / 64.0;
    EXPECT_DOUBLE_EQ(d.prepass_mean, mean) << spec;
  }
  EXPECT_FALSE(MakeSpectralEstimator(*ParsePrepass("edges64"))->Estimate(f, 99).prepass_lattice);
}

TEST(PrepassLattice, ADirectionLessPixelLeavesTheLatticePrepassOut) {
  // A lattice is no net, so there is no sequence to continue: the pixel's
  // estimate is the sampler's own Owen-Sobol one, exactly; with the count
  // weights on every pixel (--reuse-prepass unbiased) the pre-pass is
  // weighted in as an Owen-Sobol one would be.
  constexpr uint32_t kN = 256;
  const Scene scene = *MakeScene("shadow", 64, 64, 2);
  const std::vector<PixelClass> classes = scene.Classes();
  const auto estimator = MakeSpectralEstimator(*ParsePrepass("edges64l"));
  std::vector<PixelDirection> dirs(scene.size());
  RenderSets empty;
  empty.n = kN;
  empty.construction = "lattice";
  const auto alone = DirectionLessLatticeSampler(dirs, empty, false, true);
  const auto continued = DirectionLessLatticeSampler(dirs, empty, true, true);
  const auto weighted = DirectionLessLatticeSampler(dirs, empty, true, false);
  ASSERT_TRUE(alone && continued && weighted);
  int checked = 0;
  for (size_t i = 0; i < classes.size() && checked < 4; i += 41) {
    if (classes[i] != PixelClass::kSmooth) continue;
    dirs[i] = estimator->Estimate(scene.Pixel(i), HashCombine(5, i));
    ASSERT_EQ(dirs[i].kind, PixelDirection::Kind::kNone) << "smooth pixel " << i;
    ASSERT_TRUE(dirs[i].prepass_lattice);
    const int x = int(i % scene.width()), y = int(i / scene.width());
    const double own = RenderPixel(scene, *alone, x, y, 3);
    EXPECT_EQ(RenderPixel(scene, *continued, x, y, 3), own) << "pixel " << i;
    EXPECT_NEAR(RenderPixel(scene, *weighted, x, y, 3), WithPrepass(dirs[i], own, kN), 1e-15) << "pixel " << i;
    ++checked;
  }
  EXPECT_EQ(checked, 4);
}

// Edge pixels (one and two directions) and smooth ones of a scene.
std::vector<size_t> SomePixels(const Scene& scene, const std::vector<PixelDirection>& exact) {
  const std::vector<PixelClass> classes = scene.Classes();
  std::vector<size_t> out;
  int one = 0, two = 0, smooth = 0;
  for (size_t k = 0; k < classes.size(); ++k) {
    const size_t i = (k * 7919 + 57) % classes.size();
    const bool edge = classes[i] == PixelClass::kEdge;
    if (edge && exact[i].kind == PixelDirection::Kind::kOne && one < 3) out.push_back(i), ++one;
    if (edge && exact[i].kind == PixelDirection::Kind::kTwo && two < 1) out.push_back(i), ++two;
    if (classes[i] == PixelClass::kSmooth && smooth < 2) out.push_back(i), ++smooth;
  }
  return out;
}

TEST(PrepassReuse, TheReusedEstimateIsUnbiasedOverRedrawnPrepasses) {
  constexpr int kReps = 96;
  constexpr uint32_t kN = 256;
  for (const char* spec : {"edges256c50", "samples256c50", "edges256c50l"})
  for (const char* name : {"antialias", "shadow"}) {
    const auto estimator = MakeSpectralEstimator(*ParsePrepass(spec));
    const Scene scene = *MakeScene(name, 96, 96, 3);
    const std::vector<PixelDirection> exact = GeometryDirections(scene);
    const std::vector<size_t> pixels = SomePixels(scene, exact);
    ASSERT_EQ(pixels.size(), 6u) << name;
    // Each replicate's pre-pass, seeded as EstimateDirections seeds a render
    // of that seed; every direction any replicate finds gets its lattice.
    std::vector<std::vector<PixelDirection>> per_rep(kReps + 1,
                                                     std::vector<PixelDirection>(scene.size()));
    std::vector<const std::vector<PixelDirection>*> maps;
    for (int r = 1; r <= kReps; ++r) {
      for (size_t i : pixels) per_rep[r][i] = estimator->Estimate(scene.Pixel(i), HashCombine(r, i));
      maps.push_back(&per_rep[r]);
    }
    // The replicates must exercise both branches: sets chosen by a found
    // direction, and Owen-Sobol for pixels the pre-pass found none in.
    int found = 0, none = 0;
    for (int r = 1; r <= kReps; ++r) {
      for (size_t i : pixels) (per_rep[r][i].kind == PixelDirection::Kind::kNone ? none : found) += 1;
    }
    EXPECT_GT(found, kReps / 4) << spec << " " << name;
    EXPECT_GT(none, kReps) << spec << " " << name;
    auto table = AlignedLatticeTable(kN, maps, AlignedPolicy{}, 1.0, 2, nullptr);
    ASSERT_TRUE(table.ok()) << table.status().message();
    std::vector<PixelDirection> dirs(scene.size());
    for (bool reuse : {true, false}) {
      for (const char* sampler : {"aligned-lattice", "pmj02bn-sheared"}) {
        SamplerConfig c{sampler, kN};
        c.estimated = &dirs;
        c.sets = &*table;
        c.reuse_prepass = reuse;
        c.continue_prepass = false;  // the count weights on every pixel: --reuse-prepass unbiased
        auto s = MakePixelSampler(c);
        ASSERT_TRUE(s.ok()) << s.status().message();
        for (size_t i : pixels) {
          std::vector<double> e;
          for (int r = 1; r <= kReps; ++r) {
            dirs[i] = per_rep[r][i];
            e.push_back(RenderPixel(scene, **s, int(i % scene.width()), int(i / scene.width()), r));
          }
          double mean = 0.0, var = 0.0;
          for (double v : e) mean += v / kReps;
          for (double v : e) var += (v - mean) * (v - mean) / (kReps - 1);
          const double se = std::sqrt(var / kReps);
          ASSERT_TRUE(std::isfinite(mean)) << name << " " << sampler << " pixel " << i;
          EXPECT_NEAR(mean, scene.Pixel(i).Exact(), 3.0 * se + 1e-12)
              << spec << " " << name << " " << sampler << (reuse ? " reused" : "") << " pixel " << i;
        }
      }
    }
  }
}

TEST(PrepassReuse, ADirectionLessPixelContinuesThePrepassSequenceToOwenSobolAtNPlusP) {
  // The continued estimate is, to rounding, made of the first P + N points
  // of the pre-pass's own scramble: at P + N = 512 their mean (exactly what
  // Owen-Sobol gets at that total), at 320 the means of points 0-255 and
  // 256-319 weighted 256^3 : 64^3.
  constexpr uint32_t kN = 256;
  const Scene scene = *MakeScene("shadow", 64, 64, 2);
  const std::vector<PixelClass> classes = scene.Classes();
  for (const char* spec : {"edges64", "samples256c50"}) {
    const auto estimator = MakeSpectralEstimator(*ParsePrepass(spec));
    int checked = 0;
    for (size_t i = 0; i < classes.size() && checked < 4; i += 41) {
      if (classes[i] != PixelClass::kSmooth) continue;
      const PixelDirection d = estimator->Estimate(scene.Pixel(i), HashCombine(5, i));
      ASSERT_EQ(d.kind, PixelDirection::Kind::kNone) << spec << " smooth pixel " << i;
      const PointSet points = OwenScrambledSobol(d.prepass_samples + kN, HashCombine(5, i));
      double head = 0.0, tail = 0.0;
      for (size_t k = 0; k < points.size(); ++k) {
        (k < 256 ? head : tail) += scene.Pixel(i).Eval({points[k].x, points[k].y});
      }
      const double direct = points.size() == 512 ? (head + tail) / 512.0
                                                 : (64.0 * head / 256.0 + tail / 64.0) / 65.0;
      EXPECT_NEAR(ContinuedPrepass(scene.Pixel(i), d, kN), direct, 1e-12) << spec << " pixel " << i;
      ++checked;
    }
    EXPECT_EQ(checked, 4) << spec;
  }
}

TEST(PrepassReuse, ContinuingTheSequenceBeatsWeightingOnSmoothPixels) {
  // A direction-less pixel gets Owen-Sobol at N. With the pre-pass (256
  // Owen-Sobol samples, weight 1/3 at N = 256) weighted in, two independent
  // estimators of the same variance v combine to (1/9 + 4/9) v = 0.56 v;
  // continued, the pixel is a net of 512 points, about v / 8 where the
  // pixel is smooth (n^-3).
  constexpr int kReps = 64;
  constexpr uint32_t kN = 256;
  const Scene scene = *MakeScene("shadow", 64, 64, 2);
  const std::vector<PixelClass> classes = scene.Classes();
  const auto estimator = MakeSpectralEstimator(*ParsePrepass("samples256c50"));
  std::vector<PixelDirection> dirs(scene.size());
  RenderSets empty;
  empty.n = kN;
  empty.construction = "lattice";
  enum Mode { kAlone, kWeighted, kContinued };
  double var[3] = {0.0, 0.0, 0.0};
  int counted = 0;
  for (size_t i = 0; i < classes.size() && counted < 6; i += 37) {
    if (classes[i] != PixelClass::kSmooth) continue;
    for (Mode mode : {kAlone, kWeighted, kContinued}) {
      const auto s = DirectionLessLatticeSampler(dirs, empty, mode != kAlone, mode == kContinued);
      ASSERT_TRUE(s);
      double sum2 = 0.0;
      for (int r = 1; r <= kReps; ++r) {
        dirs[i] = estimator->Estimate(scene.Pixel(i), HashCombine(r, i));
        ASSERT_EQ(dirs[i].kind, PixelDirection::Kind::kNone) << "smooth pixel " << i << " replicate " << r;
        const double v = RenderPixel(scene, *s, int(i % scene.width()), int(i / scene.width()), r) -
                         scene.Pixel(i).Exact();
        sum2 += v * v;
      }
      var[mode] += sum2 / kReps;
    }
    ++counted;
  }
  ASSERT_EQ(counted, 6);
  std::printf("smooth pixels, squared error / Owen-Sobol at N: weighted %.3g, continued %.3g\n",
              var[kWeighted] / var[kAlone], var[kContinued] / var[kAlone]);
  EXPECT_LT(var[kWeighted], 0.75 * var[kAlone]);
  EXPECT_LT(var[kContinued], 0.35 * var[kAlone]);
  EXPECT_LT(var[kContinued], 0.6 * var[kWeighted]);
}

TEST(PrepassReuse, TheContinuationsSelectionBiasIsSmallOnBorderlinePixels) {
  // The price of the continuation (render/prepass_reuse.h): on an edge pixel
  // where the pre-pass finds a direction in some draws and not in others,
  // the branch is correlated with the pre-pass's error. Over many redrawn
  // pre-passes the mean of the renderer's default estimate (aligned-lattice,
  // reused, continued) is measured against the exact pixel: the bias must
  // stay within a fifth of the estimate's own RMS error (a squared bias
  // under 4% of its MSE), on the borderline pixels of both scenes.
  constexpr int kReps = 1500;
  for (auto [spec, n] : {std::pair{"edges64", 256u}, std::pair{"edges256", 1024u}, std::pair{"edges64l", 256u}})
  for (const char* name : {"antialias", "shadow"}) {
    const auto estimator = MakeSpectralEstimator(*ParsePrepass(spec));
    const Scene scene = *MakeScene(name, 96, 96, 3);
    const std::vector<PixelClass> classes = scene.Classes();
    std::vector<size_t> borderline;
    for (size_t k = 0; k < classes.size() && borderline.size() < 3; ++k) {
      const size_t i = (k * 7919 + 57) % classes.size();
      if (classes[i] != PixelClass::kEdge) continue;
      int found = 0;
      for (int r = 0; r < 24; ++r) {
        found += estimator->Estimate(scene.Pixel(i), HashCombine(1000 + r, i)).kind != PixelDirection::Kind::kNone;
      }
      if (found >= 6 && found <= 18) borderline.push_back(i);
    }
    ASSERT_EQ(borderline.size(), 3u) << spec << " " << name;
    // Every direction a draw finds, listed for the lattice table.
    std::vector<std::vector<PixelDirection>> per_pixel(borderline.size());
    std::vector<PixelDirection> all;
    for (size_t b = 0; b < borderline.size(); ++b) {
      for (int r = 1; r <= kReps; ++r) {
        per_pixel[b].push_back(estimator->Estimate(scene.Pixel(borderline[b]), HashCombine(r, borderline[b])));
        all.push_back(per_pixel[b].back());
      }
    }
    auto table = AlignedLatticeTable(n, {&all}, AlignedPolicy{}, 1.0, 2, nullptr);
    ASSERT_TRUE(table.ok()) << table.status().message();
    std::vector<PixelDirection> dirs(scene.size());
    SamplerConfig c{"aligned-lattice", n};
    c.estimated = &dirs;
    c.sets = &*table;
    c.reuse_prepass = true;
    auto s = MakePixelSampler(c);
    ASSERT_TRUE(s.ok()) << s.status().message();
    for (size_t b = 0; b < borderline.size(); ++b) {
      const size_t i = borderline[b];
      const double exact = scene.Pixel(i).Exact();
      double sum = 0.0, sum2 = 0.0;
      for (int r = 1; r <= kReps; ++r) {
        dirs[i] = per_pixel[b][r - 1];
        const double e = RenderPixel(scene, **s, int(i % scene.width()), int(i / scene.width()), r) - exact;
        sum += e, sum2 += e * e;
      }
      const double bias = sum / kReps, rmse = std::sqrt(sum2 / kReps);
      const double se = std::sqrt(std::max(0.0, sum2 / kReps - bias * bias) / kReps);
      std::printf("%s %s N=%u pixel %zu: bias %.3g (%.1f SE), RMS error %.3g, bias / RMS %.3f\n", spec,
                  name, n, i, bias, bias / se, rmse, std::fabs(bias) / rmse);
      EXPECT_LT(std::fabs(bias), 0.2 * rmse + 3.0 * se) << spec << " " << name << " pixel " << i;
    }
  }
}

TEST(PrepassReuse, OnlyTheOwenSobolPrepassIsAsGoodAnEstimateAsTheSamplersOwn) {
  // Why reuse takes samplesM only (render/spectral_estimator.h): over
  // one-direction edge pixels and smooth pixels of both scenes, the squared
  // error of each pre-pass's mean (256 evaluations) against Owen-Sobol's at
  // 256, the same replicates.
  constexpr int kReps = 48;
  for (const char* name : {"antialias", "shadow"}) {
    const Scene scene = *MakeScene(name, 64, 64, 2);
    const std::vector<PixelClass> classes = scene.Classes();
    const std::vector<PixelDirection> exact = GeometryDirections(scene);
    auto os = MakePixelSampler({"owen-sobol", 256});
    ASSERT_TRUE(os.ok());
    for (bool edge : {false, true}) {
      std::vector<size_t> px;
      for (size_t i = 0; i < classes.size() && px.size() < 12; i += 37) {
        const bool one_edge = classes[i] == PixelClass::kEdge && exact[i].kind == PixelDirection::Kind::kOne;
        if (edge ? one_edge : classes[i] == PixelClass::kSmooth) px.push_back(i);
      }
      ASSERT_EQ(px.size(), 12u) << name;
      double os_err = 0.0;
      for (size_t i : px) {
        for (int r = 1; r <= kReps; ++r) {
          const double e = RenderPixel(scene, **os, int(i % scene.width()), int(i / scene.width()), r) -
                           scene.Pixel(i).Exact();
          os_err += e * e;
        }
      }
      for (const char* spec : {"samples256c50", "jgrid16c50"}) {
        const Prepass p = *ParsePrepass(spec);
        const auto estimator = MakeSpectralEstimator(p);
        const bool samples = p.kind == Prepass::Kind::kSamples;
        double err = 0.0;
        for (size_t i : px) {
          for (int r = 1; r <= kReps; ++r) {
            // The jittered grid is not reusable, so its mean is recomputed
            // here from its own definition.
            double mean = 0.0;
            if (samples) {
              mean = estimator->Estimate(scene.Pixel(i), HashCombine(r, i)).prepass_mean;
            } else {
              Pcg32 rng(HashCombine(r, i));
              for (int k = 0; k < 256; ++k) {
                const double u = rng.NextDouble(), v = rng.NextDouble();
                mean += scene.Pixel(i).Eval({(k % 16 + u) / 16, (k / 16 + v) / 16}) / 256.0;
              }
            }
            err += (mean - scene.Pixel(i).Exact()) * (mean - scene.Pixel(i).Exact());
          }
        }
        const double ratio = err / os_err;
        std::printf("%s %s pixels: %s mean / Owen-Sobol squared error %.3g\n", name,
                    edge ? "edge" : "smooth", spec, ratio);
        if (samples) {
          EXPECT_GT(ratio, 0.5) << name << (edge ? " edge" : " smooth");
          EXPECT_LT(ratio, 2.0) << name << (edge ? " edge" : " smooth");
        } else {
          EXPECT_GT(ratio, edge ? 1.5 : 100.0) << name << (edge ? " edge" : " smooth");
        }
      }
    }
  }
}

}  // namespace
}  // namespace alignset::render

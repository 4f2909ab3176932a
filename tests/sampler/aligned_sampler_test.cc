// The per-pixel recipe as a renderer drives it: points are a function of
// (seed, pixel), the pre-pass finds an edge's direction, every estimate is
// unbiased, edge pixels beat Owen-Sobol at the same total samples, and bad
// input is refused.
#include <alignset/aligned_sampler.h>

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <thread>
#include <vector>

#include "core/optimize/lattice_sequence.h"
#include "core/sampling/owen_sobol.h"
#include "core/util/directions.h"
#include "core/util/hash.h"
#include "tests/sampler/table_fixture.h"

namespace alignset {
namespace {

// An image whose pixels integrate f over [x, x+1) x [y, y+1) (footprints),
// or all over the same [0,1)^2 with a per-pixel f (shared).
using ImageFn = std::function<double(uint32_t x, uint32_t y, double u, double v)>;

// The area of {p in [0,1]^2 : n . p > c}: the unit square clipped by a
// half-plane (Sutherland-Hodgman on four vertices), exact.
double HalfPlaneArea(double nx, double ny, double c) {
  std::vector<std::pair<double, double>> poly = {{0, 0}, {1, 0}, {1, 1}, {0, 1}}, out;
  for (size_t i = 0; i < poly.size(); ++i) {
    auto [ax, ay] = poly[i];
    auto [bx, by] = poly[(i + 1) % poly.size()];
    const double da = nx * ax + ny * ay - c, db = nx * bx + ny * by - c;
    if (da > 0) out.push_back({ax, ay});
    if ((da > 0) != (db > 0)) {
      const double t = da / (da - db);
      out.push_back({ax + t * (bx - ax), ay + t * (by - ay)});
    }
  }
  double area = 0.0;
  for (size_t i = 0; i < out.size(); ++i) {
    auto [ax, ay] = out[i];
    auto [bx, by] = out[(i + 1) % out.size()];
    area += ax * by - bx * ay;
  }
  return 0.5 * std::abs(area);
}

// A straight edge through the image: normal at theta_deg through (cx, cy),
// in image coordinates (pixels).
struct Edge {
  double theta_deg, cx, cy;
  double nx() const { return std::cos(theta_deg * M_PI / 180.0); }
  double ny() const { return std::sin(theta_deg * M_PI / 180.0); }
  double At(uint32_t x, uint32_t y, double u, double v) const {
    return nx() * (x + u - cx) + ny() * (y + v - cy) > 0.0 ? 1.0 : 0.0;
  }
  double Exact(uint32_t x, uint32_t y) const {
    return HalfPlaneArea(nx(), ny(), nx() * (cx - x) + ny() * (cy - y));
  }
};

// Runs the whole recipe on pixel (x, y) of a w x h image.
struct Rendered {
  PixelPlan plan;
  double estimate;
};
Rendered RenderPixel(const AlignedSampler& s, AlignedSampler::Scratch& scratch, uint32_t x, uint32_t y, uint32_t w,
                     uint32_t h, const ImageFn& f) {
  const int r = s.block_radius(), side = s.block_side();
  std::vector<std::vector<double>> values(static_cast<size_t>(side * side));
  std::vector<std::span<const double>> block(values.size());
  std::vector<Point2> pts(s.prepass_samples());
  for (int k = 0; k < side * side; ++k) {
    const int64_t nx = static_cast<int64_t>(x) + k % side - r, ny = static_cast<int64_t>(y) + k / side - r;
    if (nx < 0 || ny < 0 || nx >= w || ny >= h) continue;
    s.PrepassPoints(static_cast<uint32_t>(nx), static_cast<uint32_t>(ny), pts);
    for (const Point2& p : pts) values[k].push_back(f(static_cast<uint32_t>(nx), static_cast<uint32_t>(ny), p.x, p.y));
    block[k] = values[k];
  }
  auto plan = s.Plan(x, y, block, scratch);
  EXPECT_TRUE(plan.ok()) << plan.status().message();
  std::vector<Point2> main(s.n());
  s.MainPoints(*plan, main);
  std::vector<double> mv;
  for (const Point2& p : main) {
    EXPECT_TRUE(p.x >= 0.0 && p.x < 1.0 && p.y >= 0.0 && p.y < 1.0);
    mv.push_back(f(x, y, p.x, p.y));
  }
  return {*plan, s.Estimate(*plan, values[static_cast<size_t>(side * side / 2)], mv)};
}

class AlignedSamplerTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    auto t = SetTable::FromSections({testing::LatticeSection(256, TableSpace::kOneDirection),
                                     testing::LatticeSection(64, TableSpace::kOneDirection)});
    ASSERT_TRUE(t.ok());
    table_ = new std::shared_ptr<const SetTable>(*t);
  }
  static void TearDownTestSuite() { delete table_; }
  static AlignedSampler Make(AlignedSamplerOptions o) {
    auto s = AlignedSampler::Create(*table_, o);
    EXPECT_TRUE(s.ok()) << s.status().message();
    return *s;
  }
  static std::shared_ptr<const SetTable>* table_;
};
std::shared_ptr<const SetTable>* AlignedSamplerTest::table_ = nullptr;

AlignedSamplerOptions Options(uint32_t n, uint32_t width, PixelDomain d = PixelDomain::kFootprint) {
  AlignedSamplerOptions o;
  o.n = n;
  o.image_width = width;
  o.domain = d;
  return o;
}

TEST_F(AlignedSamplerTest, DefaultsAreTheRendersMeasuredOnes) {
  const AlignedSampler s256 = Make(Options(256, 16));
  EXPECT_EQ(s256.prepass_samples(), 64u);
  EXPECT_EQ(s256.block_side(), 3);
  EXPECT_TRUE(s256.lattice_prepass());
  const AlignedSampler shared = Make(Options(256, 16, PixelDomain::kShared));
  EXPECT_EQ(shared.block_side(), 5);
  const AlignedSampler s64 = Make(Options(64, 16));
  EXPECT_EQ(s64.prepass_samples(), 16u);
  // w = M^1.5 / (M^1.5 + 2 N^1.5) at M = 64, N = 256: 512 / (512 + 8192).
  EXPECT_NEAR(s256.PrepassWeight(), 512.0 / 8704.0, 1e-15);
}

TEST_F(AlignedSamplerTest, PrepassPointsAreAFunctionOfSeedAndPixelAndStratified) {
  const AlignedSampler s = Make(Options(256, 16));
  std::vector<Point2> a(64), b(64), c(64);
  s.PrepassPoints(3, 5, a);
  s.PrepassPoints(3, 5, b);
  s.PrepassPoints(5, 3, c);
  EXPECT_EQ(a, b);
  EXPECT_NE(a, c);
  // A shifted rank-1 lattice: one point in each column of width 1/M.
  std::vector<int> columns(64, 0);
  for (const Point2& p : a) {
    ASSERT_TRUE(p.x >= 0.0 && p.x < 1.0 && p.y >= 0.0 && p.y < 1.0);
    ++columns[static_cast<int>(p.x * 64)];
  }
  for (int k : columns) EXPECT_EQ(k, 1);
  AlignedSamplerOptions other = Options(256, 16);
  other.seed = 2;
  std::vector<Point2> d(64);
  Make(other).PrepassPoints(3, 5, d);
  EXPECT_NE(a, d);
  // Owen-Sobol pre-pass points on request: a (0,6,2)-net prefix of that sequence.
  other.prepass_points = AlignedSamplerOptions::PrepassPoints::kOwenSobol;
  Make(other).PrepassPoints(3, 5, d);
  const uint64_t h = HashCombine(2, 5 * 16 + 3);
  EXPECT_EQ(d, OwenScrambledSobol(64, h));
}

TEST_F(AlignedSamplerTest, ThePlanFollowsTheEdgeAndTheMainPointsAreItsLattice) {
  const AlignedSampler s = Make(Options(256, 12));
  AlignedSampler::Scratch scratch;
  for (double theta : {13.0, 37.0, 62.0, 101.0, 148.0}) {
    SCOPED_TRACE(theta);
    const Edge e{theta, 6.4, 6.3};
    const Rendered r = RenderPixel(s, scratch, 6, 6, 12, 12, [&](uint32_t x, uint32_t y, double u, double v) {
      return e.At(x, y, u, v);
    });
    ASSERT_GE(r.plan.directions, 1);
    EXPECT_LT(AxialDistanceDeg(r.plan.theta1_deg, theta), 3.0) << r.plan.theta1_deg;
    ASSERT_EQ(r.plan.choice.kind, SetChoice::Kind::kOne);
    EXPECT_EQ(r.plan.main, PixelPlan::Main::kSet);
    auto set = (*table_)->Find(256, "lattice", r.plan.choice);
    ASSERT_TRUE(set.ok());
    EXPECT_EQ(r.plan.set.lattice_generator, set->lattice_generator);
    // The main points are that lattice under one shift: differences of
    // points are lattice vectors (i, i g) / N mod 1.
    std::vector<Point2> pts(256);
    s.MainPoints(r.plan, pts);
    const uint32_t g = set->lattice_generator;
    for (uint32_t i = 1; i < 256; i += 37) {
      const double dx = std::remainder(pts[i].x - pts[0].x - i / 256.0, 1.0);
      const double dy = std::remainder(pts[i].y - pts[0].y - static_cast<double>((uint64_t{i} * g) % 256) / 256.0, 1.0);
      EXPECT_NEAR(dx, 0.0, 1e-12);
      EXPECT_NEAR(dy, 0.0, 1e-12);
    }
  }
  // A smooth pixel has no direction: its own Owen-Sobol points.
  const Rendered smooth = RenderPixel(s, scratch, 2, 2, 12, 12, [](uint32_t x, uint32_t y, double u, double v) {
    return 0.1 * (x + u) + 0.05 * (y + v);
  });
  EXPECT_EQ(smooth.plan.directions, 0);
  EXPECT_EQ(smooth.plan.choice.kind, SetChoice::Kind::kFallback);
  EXPECT_EQ(smooth.plan.main, PixelPlan::Main::kOwenSobol);
  EXPECT_EQ(scratch.stats().pixels, 6u);
  EXPECT_EQ(scratch.stats().with_direction, 5u);
}

// A table of lattice sequences: the sampler says it is progressive, the
// first k main points of a planned pixel are the first k of its N (the
// sequence's prefix under the pixel's shift, each power-of-two prefix a
// lattice), and an estimate from k main values weighs the pre-pass as
// beside k. A fixed-size lattice's sampler is not progressive.
TEST_F(AlignedSamplerTest, ALatticeSequenceTableIsProgressive) {
  TableSection seq;
  seq.n = 1024;
  seq.construction = "lattice-sequence";
  seq.space = TableSpace::kOneDirection;
  for (uint32_t k = 0; k < TableSpaceKeys(TableSpace::kOneDirection); ++k) {
    seq.sets.push_back(LatticeSequencePoints(1024, 2 * k + 4001, 0));
  }
  auto made = SetTable::FromSections({std::move(seq)});
  ASSERT_TRUE(made.ok()) << made.status().message();
  // Through the file's bytes: the sequence's points survive bit for bit.
  auto t = SetTable::Parse((*made)->Serialize());
  ASSERT_TRUE(t.ok()) << t.status().message();
  EXPECT_EQ((*t)->sections().front().sets, (*made)->sections().front().sets);
  EXPECT_EQ((*t)->PointCounts("lattice-sequence"), std::vector<uint32_t>{1024});
  AlignedSamplerOptions o = Options(1024, 12);
  o.construction = "lattice-sequence";
  auto s = AlignedSampler::Create(*t, o);
  ASSERT_TRUE(s.ok()) << s.status().message();
  EXPECT_TRUE(s->progressive());
  EXPECT_FALSE(Make(Options(256, 12)).progressive());
  AlignedSampler::Scratch scratch;
  const Edge e{41.0, 6.4, 6.3};
  const ImageFn f = [&](uint32_t x, uint32_t y, double u, double v) { return e.At(x, y, u, v); };
  const Rendered r = RenderPixel(*s, scratch, 6, 6, 12, 12, f);
  ASSERT_EQ(r.plan.main, PixelPlan::Main::kSet);
  std::vector<Point2> all(1024), part(100);
  s->MainPoints(r.plan, all);
  s->MainPoints(r.plan, part);
  for (size_t i = 0; i < part.size(); ++i) EXPECT_EQ(part[i], all[i]);
  // The first 64 are a shifted lattice: one point in each column of 1/64.
  std::vector<int> columns(64, 0);
  for (size_t i = 0; i < 64; ++i) ++columns[static_cast<size_t>(all[i].x * 64)];
  for (int c : columns) EXPECT_EQ(c, 1);
  const std::vector<double> pre(s->prepass_samples(), 1.0), main(64, 0.0);
  const double w = PrepassWeight(s->prepass_samples(), 64);
  EXPECT_NEAR(s->Estimate(r.plan, pre, main), w, 1e-15);
  EXPECT_GT(w, s->PrepassWeight());
}

TEST_F(AlignedSamplerTest, ASharedDomainsStackedBlockFindsTheEdge) {
  const AlignedSampler s = Make(Options(256, 9, PixelDomain::kShared));
  AlignedSampler::Scratch scratch;
  // Every pixel integrates over one light square; its shadow edge moves a
  // little from pixel to pixel (a penumbra seen from neighbouring points).
  const double theta = 71.0, n_x = std::cos(theta * M_PI / 180), n_y = std::sin(theta * M_PI / 180);
  const Rendered r = RenderPixel(s, scratch, 4, 4, 9, 9, [&](uint32_t x, uint32_t y, double u, double v) {
    return n_x * (u - 0.5) + n_y * (v - 0.5) > 0.03 * (static_cast<double>(x) - 4.0) ? 1.0 : 0.2;
  });
  ASSERT_GE(r.plan.directions, 1);
  EXPECT_LT(AxialDistanceDeg(r.plan.theta1_deg, theta), 3.0) << r.plan.theta1_deg;
}

// Unbiased on every kind of pixel: the mean estimate over seeds within
// four standard errors of the exact integral.
TEST_F(AlignedSamplerTest, EveryEstimateIsUnbiased) {
  const Edge e{23.0, 5.45, 5.6};
  struct Case {
    const char* what;
    ImageFn f;
    double exact;
  };
  const std::vector<Case> cases = {
      {"edge", [&](uint32_t x, uint32_t y, double u, double v) { return e.At(x, y, u, v); }, e.Exact(5, 5)},
      {"smooth, not periodic", [](uint32_t x, uint32_t y, double u, double v) { return std::exp(-u) * (1.0 + v * v); },
       (1.0 - std::exp(-1.0)) * (4.0 / 3.0)},
  };
  for (PrepassReuse reuse : {PrepassReuse::kUnbiased}) {
    for (const Case& c : cases) {
      SCOPED_TRACE(c.what);
      double sum = 0.0, sum2 = 0.0;
      const int runs = 300;
      AlignedSampler::Scratch scratch;
      for (int seed = 1; seed <= runs; ++seed) {
        AlignedSamplerOptions o = Options(64, 11);
        o.seed = static_cast<uint64_t>(seed) * 7919;
        o.reuse = reuse;
        const double v = RenderPixel(Make(o), scratch, 5, 5, 11, 11, c.f).estimate;
        sum += v;
        sum2 += v * v;
      }
      const double mean = sum / runs, var = std::max(0.0, sum2 / runs - mean * mean);
      const double se = std::sqrt(var / runs);
      EXPECT_LT(std::abs(mean - c.exact), 4.0 * se + 1e-12) << "mean " << mean << " exact " << c.exact << " se " << se;
    }
  }
}

// The point of it all: on edge pixels at angles nobody tuned on, less error
// than Owen-Sobol given every sample the recipe spends (M + N).
TEST_F(AlignedSamplerTest, EdgePixelsBeatOwenSobolAtTheSameTotalSamples) {
  const AlignedSampler s = Make(Options(256, 12));
  AlignedSampler::Scratch scratch;
  double ours = 0.0, owen = 0.0;
  int pixels = 0;
  for (int k = 0; k < 24; ++k) {
    const double theta = 3.7 + 7.3 * k;  // 3.7 ... 171.6 degrees
    const Edge e{theta, 6.0 + 0.37 * std::sin(k), 6.0 + 0.41 * std::cos(3 * k)};
    const ImageFn f = [&](uint32_t x, uint32_t y, double u, double v) { return e.At(x, y, u, v); };
    for (uint32_t x = 4; x <= 7; ++x) {
      for (uint32_t y = 4; y <= 7; ++y) {
        const double exact = e.Exact(x, y);
        if (exact < 0.02 || exact > 0.98) continue;  // the edge must cross the pixel
        const double a = RenderPixel(s, scratch, x, y, 12, 12, f).estimate - exact;
        const PointSet os = OwenScrambledSobol(256 + 64, 5000 + 131 * k + 11 * x + y);
        double m = 0.0;
        for (const Point2& p : os) m += f(x, y, p.x, p.y);
        const double b = m / os.size() - exact;
        ours += a * a;
        owen += b * b;
        ++pixels;
      }
    }
  }
  ASSERT_GE(pixels, 48);
  RecordProperty("owen_sobol_over_aligned", std::to_string(owen / ours));
  EXPECT_GT(owen / ours, 2.0) << "Owen-Sobol at 320 over aligned 256 + 64 on " << pixels << " edge pixels";
}

TEST_F(AlignedSamplerTest, TheSameOnEveryThread) {
  const AlignedSampler s = Make(Options(256, 12));
  const Edge e{41.0, 6.2, 6.1};
  const ImageFn f = [&](uint32_t x, uint32_t y, double u, double v) { return e.At(x, y, u, v); };
  std::vector<double> got(4);
  std::vector<std::thread> threads;
  for (int t = 0; t < 4; ++t) {
    threads.emplace_back([&, t] {
      AlignedSampler::Scratch scratch;
      got[t] = RenderPixel(s, scratch, 6, 6, 12, 12, f).estimate;
    });
  }
  for (auto& t : threads) t.join();
  for (int t = 1; t < 4; ++t) EXPECT_EQ(got[t], got[0]);
}

TEST_F(AlignedSamplerTest, APairTheTableLacksReadsTheStrongerDirectionsSet) {
  const AlignedSampler s = Make(Options(256, 12));
  AlignedSampler::Scratch scratch;
  // A corner: two edges at 20 and 110 degrees meet in the pixel.
  const Edge a{20.0, 6.5, 6.5}, b{110.0, 6.5, 6.5};
  const Rendered r = RenderPixel(s, scratch, 6, 6, 12, 12, [&](uint32_t x, uint32_t y, double u, double v) {
    return a.At(x, y, u, v) * b.At(x, y, u, v);
  });
  if (r.plan.directions == 2) {
    EXPECT_TRUE(r.plan.pair_fell_back);
    EXPECT_EQ(r.plan.choice.kind, SetChoice::Kind::kOne);
    EXPECT_EQ(r.plan.choice.a, ServedDegree(r.plan.theta1_deg));
    EXPECT_EQ(scratch.stats().pair_fell_back, 1u);
  } else {
    EXPECT_FALSE(r.plan.pair_fell_back);
  }
}

// A table whose pair section holds only some keys (a render's, or a file
// of format version 2): a pixel whose pair it holds reads it; another falls
// back to the stronger direction as from a table without pairs.
TEST_F(AlignedSamplerTest, APairSectionOfSomeKeysServesThemAndFallsBackFromTheRest) {
  const Edge a{20.0, 6.5, 6.5}, b{110.0, 6.5, 6.5};
  const auto corner = [&](uint32_t x, uint32_t y, double u, double v) { return a.At(x, y, u, v) * b.At(x, y, u, v); };
  AlignedSampler::Scratch scratch;
  const Rendered first = RenderPixel(Make(Options(256, 12)), scratch, 6, 6, 12, 12, corner);
  ASSERT_EQ(first.plan.directions, 2) << "the corner's pre-pass must find both edges";
  AlignedPolicy both;
  const SetChoice pair = ChooseSet({2, first.plan.theta1_deg, first.plan.theta2_deg}, both);
  ASSERT_EQ(pair.kind, SetChoice::Kind::kTwo);
  const auto how = Canonicalize({static_cast<double>(pair.a), static_cast<double>(pair.b)});
  const uint32_t key = static_cast<uint32_t>(*CanonicalKeyIndex(how->key));
  for (const bool holds : {true, false}) {
    SCOPED_TRACE(holds ? "the pair's key held" : "another key held");
    TableSection some;
    some.n = 256;
    some.construction = "lattice";
    some.space = TableSpace::kTwoDirections;
    some.keys = {holds ? key : (key == 0 ? 1u : 0u)};
    some.generators = {1};
    auto t = SetTable::FromSections({(*table_)->sections()[0], some});
    ASSERT_TRUE(t.ok()) << t.status().message();
    auto s = AlignedSampler::Create(*t, Options(256, 12));
    ASSERT_TRUE(s.ok()) << s.status().message();
    AlignedSampler::Scratch fresh;
    const Rendered r = RenderPixel(*s, fresh, 6, 6, 12, 12, corner);
    ASSERT_EQ(r.plan.directions, 2);
    EXPECT_EQ(r.plan.pair_fell_back, !holds);
    EXPECT_EQ(r.plan.choice.kind, holds ? SetChoice::Kind::kTwo : SetChoice::Kind::kOne);
    if (holds) {
      EXPECT_EQ(r.plan.set.lattice_generator,
                MapLatticeGenerator(256, 1, how->ops.swap, how->ops.invert, how->ops.invert_y));
    }
  }
}

TEST_F(AlignedSamplerTest, TheContinuedSequenceWeighsItsNetsBlocks) {
  AlignedSamplerOptions o = Options(256, 8);
  o.prepass_points = AlignedSamplerOptions::PrepassPoints::kOwenSobol;
  o.reuse = PrepassReuse::kContinue;
  const AlignedSampler s = Make(o);
  PixelPlan plan;
  plan.main = PixelPlan::Main::kContinued;
  // T = 320: the 256-block (the pre-pass's 64 and the first 192 main
  // values) weighs 256^3, the 64-block 64^3.
  std::vector<double> pre(64, 1.0), main(256, 0.0);
  for (size_t k = 192; k < 256; ++k) main[k] = 2.0;
  const double w256 = std::pow(256.0, 3), w64 = std::pow(64.0, 3);
  EXPECT_NEAR(s.Estimate(plan, pre, main), (w256 * (64.0 / 256.0) + w64 * 2.0) / (w256 + w64), 1e-15);
  // Its points continue the pre-pass's sequence.
  plan.main_seed = 99;
  std::vector<Point2> pts(256);
  s.MainPoints(plan, pts);
  const PointSet all = OwenScrambledSobol(320, 99);
  EXPECT_EQ(pts, PointSet(all.begin() + 64, all.end()));
}

TEST_F(AlignedSamplerTest, BadInputIsRefusedWithAMessage) {
  AlignedSamplerOptions o = Options(512, 8);
  auto missing = AlignedSampler::Create(*table_, o);
  EXPECT_EQ(missing.status().code(), Status::Code::kNotFound);
  EXPECT_NE(missing.status().message().find("N = 512 (it has N = 64, 256)"), std::string::npos)
      << missing.status().message();
  o = Options(256, 0);
  EXPECT_EQ(AlignedSampler::Create(*table_, o).status().code(), Status::Code::kInvalidArgument);
  o = Options(256, 8);
  o.construction = "sobol";
  EXPECT_EQ(AlignedSampler::Create(*table_, o).status().code(), Status::Code::kInvalidArgument);
  o = Options(256, 8);
  o.construction = "tent-lattice";
  EXPECT_EQ(AlignedSampler::Create(*table_, o).status().code(), Status::Code::kNotFound);
  o = Options(256, 8);
  o.prepass_samples = 8;
  EXPECT_EQ(AlignedSampler::Create(*table_, o).status().code(), Status::Code::kInvalidArgument);
  EXPECT_EQ(AlignedSampler::Create(nullptr, Options(256, 8)).status().code(), Status::Code::kInvalidArgument);

  const AlignedSampler s = Make(Options(256, 8));
  AlignedSampler::Scratch scratch;
  std::vector<double> values(64, 0.5), short_values(10, 0.5);
  std::vector<std::span<const double>> four(4, values);
  EXPECT_EQ(s.Plan(1, 1, four, scratch).status().code(), Status::Code::kInvalidArgument);
  std::vector<std::span<const double>> nine(9, values);
  nine[2] = short_values;
  EXPECT_EQ(s.Plan(1, 1, nine, scratch).status().code(), Status::Code::kInvalidArgument);
  nine.assign(9, values);
  nine[4] = {};
  EXPECT_NE(s.Plan(1, 1, nine, scratch).status().message().find("centre"), std::string::npos);
}

// A Scratch keeps the crossings of the pixels it read last: a raster walk
// with one Scratch fits every pixel exactly as a fresh Scratch would, at
// every stack radius (the largest block, 9 x 9, reads 81 pixels a fit).
TEST(PrepassFitTest, AScratchReusedOverAWalkFitsAsAFreshOneDoes) {
  for (int radius : {1, 2, 3, 4}) {
    SCOPED_TRACE(radius);
    PrepassFitOptions o;
    o.domain = PixelDomain::kShared;
    o.image_width = 14;
    o.prepass_samples = 64;
    o.stack_radius = radius;
    auto fit = PrepassFit::Create(o);
    ASSERT_TRUE(fit.ok());
    const int side = fit->block_side();
    std::vector<std::vector<double>> pre(14 * 14);
    std::vector<Point2> pts(64);
    for (uint32_t y = 0; y < 14; ++y) {
      for (uint32_t x = 0; x < 14; ++x) {
        fit->PrepassPoints(x, y, pts);
        for (const Point2& p : pts) pre[y * 14 + x].push_back(p.x * 0.8 + p.y * 0.6 > 0.5 + 0.02 * x ? 1.0 : 0.0);
      }
    }
    PrepassFit::Scratch reused;
    for (uint32_t y = 0; y < 14; ++y) {
      for (uint32_t x = 0; x < 14; ++x) {
        std::vector<std::span<const double>> block(static_cast<size_t>(side * side));
        for (int k = 0; k < side * side; ++k) {
          const int bx = static_cast<int>(x) + k % side - radius, by = static_cast<int>(y) + k / side - radius;
          if (bx >= 0 && by >= 0 && bx < 14 && by < 14) block[k] = pre[by * 14 + bx];
        }
        PrepassFit::Scratch fresh;
        auto a = fit->Fit(x, y, block, reused);
        auto b = fit->Fit(x, y, block, fresh);
        ASSERT_TRUE(a.ok() && b.ok());
        ASSERT_EQ(a->directions, b->directions) << x << ", " << y;
        ASSERT_EQ(a->theta1_deg, b->theta1_deg) << x << ", " << y;
        ASSERT_EQ(a->theta2_deg, b->theta2_deg) << x << ", " << y;
      }
    }
  }
}

}  // namespace
}  // namespace alignset

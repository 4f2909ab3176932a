#include "core/analysis/direction_estimate.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "core/analysis/patch_sampling.h"
#include "core/analysis/step_integrand.h"
#include "core/spectral/direct_engine.h"
#include "core/spectral/fast_engine.h"
#include "core/util/angles.h"
#include "core/util/hash.h"

namespace alignset {
namespace {

double AngleError(double est, double truth) {
  double d = std::fmod(std::fabs(est - truth), 180.0);
  return std::min(d, 180.0 - d);
}

Integrand2 Step(double theta, double offset) {
  const StepIntegrand f(theta, offset);
  return [f](const Point2& p) { return f(p); };
}

TEST(EstimateDirection, CleanStepEdgesToAFractionOfADegree) {
  // A small version of bench/direction_accuracy's first row.
  Pcg32 rng(77);
  std::vector<double> errors;
  for (int i = 0; i < 24; ++i) {
    const double theta = 180.0 * rng.NextDouble(), offset = -0.25 + 0.5 * rng.NextDouble();
    auto r = EstimateDirection(PointSampledGrid(Step(theta, offset), 64, 64));
    ASSERT_TRUE(r.ok()) << r.status().message();
    ASSERT_EQ(r->first.status, DirectionStatus::kFound) << theta << " " << r->first.reason;
    EXPECT_GE(r->first.theta_deg, 0.0);
    EXPECT_LT(r->first.theta_deg, 180.0);
    EXPECT_GT(r->first.kappa, 1.0);
    EXPECT_GT(r->first.confidence, 0.2);
    EXPECT_LE(r->first.confidence, 1.0);
    errors.push_back(AngleError(r->first.theta_deg, theta));
    EXPECT_LT(errors.back(), 1.0) << theta << " offset " << offset;
  }
  std::sort(errors.begin(), errors.end());
  EXPECT_LT(errors[errors.size() / 2], 0.2);
}

TEST(EstimateDirection, NotRoundedToWholeDegrees) {
  auto r = EstimateDirection(PointSampledGrid(Step(33.4, 0.05), 128, 128));
  ASSERT_TRUE(r.ok());
  EXPECT_NEAR(r->first.theta_deg, 33.4, 0.25);
  EXPECT_NE(r->first.theta_deg, std::round(r->first.theta_deg));
}

TEST(EstimateDirection, RowsAreYAndTransposingGivesNinetyMinusTheta) {
  // values[j * W + i] = f((i + 1/2) / W, (j + 1/2) / H): columns along x,
  // rows along y. An edge with normal 20° read with rows and columns swapped
  // is the edge with normal 70°.
  const GridPatch g = PointSampledGrid(Step(20.0, 0.1), 48, 48);
  GridPatch t = g;
  for (int j = 0; j < 48; ++j)
    for (int i = 0; i < 48; ++i) t.values[static_cast<size_t>(i) * 48 + j] = g.values[j * 48 + i];
  auto a = EstimateDirection(g), b = EstimateDirection(t);
  ASSERT_TRUE(a.ok() && b.ok());
  EXPECT_NEAR(a->first.theta_deg, 20.0, 0.5);
  EXPECT_NEAR(b->first.theta_deg, 70.0, 0.5);
  EXPECT_NEAR(a->first.theta_deg + b->first.theta_deg, 90.0, 1e-6);
  // A vertical ramp in y (values growing with the row index) has its
  // energy along 90°.
  GridPatch ramp{32, 32, std::vector<double>(32 * 32)};
  for (int j = 0; j < 32; ++j)
    for (int i = 0; i < 32; ++i) ramp.values[j * 32 + i] = j < 16 ? 0.0 : 1.0;
  auto c = EstimateDirection(ramp);
  ASSERT_TRUE(c.ok());
  EXPECT_NEAR(AngleError(c->first.theta_deg, 90.0), 0.0, 0.01);
}

TEST(EstimateDirection, NonSquareGridsKeepTheUnitSquaresAngles) {
  auto r = EstimateDirection(PointSampledGrid(Step(30.0, 0.0), 96, 40));
  ASSERT_TRUE(r.ok());
  EXPECT_NEAR(r->first.theta_deg, 30.0, 0.5);
}

TEST(EstimateDirection, ScatteredSamplesThroughEitherEngine) {
  const SampledPatch s = RandomSamples(Step(115.0, 0.05), 4096, 3);
  DirectEngine direct(1);
  FastEngine fast(1);
  auto d = EstimateDirection(s, {}, &direct);
  auto f = EstimateDirection(s, {}, &fast);
  auto a = EstimateDirection(s);
  ASSERT_TRUE(d.ok() && f.ok() && a.ok());
  ASSERT_EQ(d->first.status, DirectionStatus::kFound) << d->first.reason;
  EXPECT_LT(AngleError(d->first.theta_deg, 115.0), 2.0);
  EXPECT_NEAR(f->first.theta_deg, d->first.theta_deg, 1e-6);
  EXPECT_NEAR(a->first.theta_deg, d->first.theta_deg, 1e-6);
  EXPECT_TRUE(std::isfinite(d->first.significance));
  EXPECT_GT(d->first.significance, 5.0);
}

TEST(EstimateDirection, NoDominantDirectionForConstantNoiseAndDisks) {
  for (double c : {0.0, 1.0, 0.1, 1e6}) {
    auto r = EstimateDirection(GridPatch{16, 16, std::vector<double>(256, c)});
    ASSERT_TRUE(r.ok());
    EXPECT_EQ(r->first.status, DirectionStatus::kNoDominantDirection) << c;
    EXPECT_NE(r->first.reason.find("constant"), std::string::npos);
    EXPECT_EQ(r->first.theta_deg, 0.0);
  }
  for (uint64_t seed = 0; seed < 4; ++seed) {
    Pcg32 rng(seed);
    GridPatch g{64, 64, std::vector<double>(4096)};
    for (double& v : g.values) v = rng.NextDouble();
    auto r = EstimateDirection(g);
    ASSERT_TRUE(r.ok());
    EXPECT_EQ(r->first.status, DirectionStatus::kNoDominantDirection) << seed;
    EXPECT_FALSE(r->first.reason.empty());

    auto noise = std::make_shared<Pcg32>(seed + 100);
    auto s = EstimateDirection(RandomSamples([noise](const Point2&) { return noise->NextDouble(); }, 1024, seed));
    ASSERT_TRUE(s.ok());
    EXPECT_EQ(s->first.status, DirectionStatus::kNoDominantDirection) << seed;
  }
  for (double radius : {0.15, 0.3}) {
    auto disk = [radius](const Point2& p) { return std::hypot(p.x - 0.47, p.y - 0.55) <= radius ? 1.0 : 0.0; };
    auto r = EstimateDirection(PointSampledGrid(disk, 64, 64));
    ASSERT_TRUE(r.ok());
    EXPECT_EQ(r->first.status, DirectionStatus::kNoDominantDirection) << radius;
    EXPECT_LT(r->first.contrast, 1.7);
  }
}

TEST(EstimateDirection, TwoCrossingEdgesStrongerFirst) {
  const StepIntegrand a(25.0, 0.05), b(110.0, -0.08);
  auto f = [&](const Point2& p) { return a(p) + 0.5 * b(p); };
  DirectionOptions o;
  o.second = true;
  auto r = EstimateDirection(PointSampledGrid(f, 64, 64), o);
  ASSERT_TRUE(r.ok());
  ASSERT_TRUE(r->has_second);
  ASSERT_EQ(r->first.status, DirectionStatus::kFound);
  ASSERT_EQ(r->second.status, DirectionStatus::kFound) << r->second.reason;
  EXPECT_LT(AngleError(r->first.theta_deg, 25.0), 1.0);
  EXPECT_LT(AngleError(r->second.theta_deg, 110.0), 1.0);
  EXPECT_GT(r->first.confidence, r->second.confidence);
  // Without the request there is no second direction.
  auto one = EstimateDirection(PointSampledGrid(f, 64, 64));
  EXPECT_FALSE(one->has_second);
}

TEST(EstimateDirection, RefusesInvalidInputAndOptions) {
  EXPECT_EQ(EstimateDirection(GridPatch{4, 4, std::vector<double>(16)}).status().code(),
            Status::Code::kInvalidArgument);
  EXPECT_EQ(EstimateDirection(SampledPatch{}).status().code(), Status::Code::kInvalidArgument);
  DirectionOptions o;
  o.bins = 3;
  EXPECT_EQ(EstimateDirection(GridPatch{8, 8, std::vector<double>(64)}, o).status().code(),
            Status::Code::kInvalidArgument);
  o = {};
  o.sigma = std::nan("");
  EXPECT_EQ(ValidateDirectionOptions(o).code(), Status::Code::kInvalidArgument);
}

}  // namespace
}  // namespace alignset

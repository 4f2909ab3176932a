#include "core/sampling/shear.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/util/angles.h"
#include "core/spectral/direct_engine.h"
#include "core/spectral/frequency_set.h"
#include "core/sampling/pmj02.h"

namespace alignset {
namespace {

double StripMean(const PointSet& p, double deg, DirectEngine* engine) {
  const FrequencyParams params = DefaultFrequencyParams(static_cast<uint32_t>(p.size()));
  std::vector<Frequency> k;
  for (const Frequency& f : StripFrequencies(params, deg)) {
    if (std::hypot(f.a, f.b) > 4.0) k.push_back(f);  // the low disk is dark anyway
  }
  engine->SetFrequencies(k);
  SpectrumEvaluation e;
  engine->Evaluate(p, false, &e);
  return e.loss;
}

TEST(Shear, AxesAreIdentitiesAndPointsStayInTheSquare) {
  const PointSet p = *Pmj02(256, 1, 1);
  EXPECT_EQ(Shear(p, 0.0), p);
  EXPECT_EQ(Shear(p, 90.0), p);
  EXPECT_EQ(Shear(p, 180.0), p);
  for (double deg : {10.0, 44.9, 45.0, 60.0, 135.0, 170.0, -20.0}) {
    for (const Point2& q : Shear(p, deg)) {
      ASSERT_TRUE(q.x >= 0.0 && q.x < 1.0 && q.y >= 0.0 && q.y < 1.0) << deg;
    }
  }
  // Algorithm 2 by hand: 30° shears x by tan 30°, 60° shears y by cot 60°.
  const PointSet one = {{0.5, 0.25}};
  EXPECT_NEAR(Shear(one, 30.0)[0].x, 0.5 - std::tan(kPi / 6) * 0.25, 1e-15);
  EXPECT_EQ(Shear(one, 30.0)[0].y, 0.25);
  EXPECT_NEAR(Shear(one, 60.0)[0].y, 1.0 + 0.25 - 0.5 / std::tan(kPi / 3), 1e-15);  // wrapped mod 1
  EXPECT_EQ(Shear(one, 60.0)[0].x, 0.5);
}

TEST(Shear, MovesTheDarkAxisOntoTheRequestedDirection) {
  // pmj02 is dark along the axes; sheared to θ its strip along θ darkens
  // (the seam keeps it from being as dark as the axes were).
  DirectEngine engine(2);
  double before = 0, after = 0;
  for (uint64_t seed = 1; seed <= 3; ++seed) {
    const PointSet p = *Pmj02(1024, seed, kPmj02bnCandidates);
    for (double deg : {20.0, 70.0, 160.0}) {
      before += StripMean(p, deg, &engine);
      after += StripMean(Shear(p, deg), deg, &engine);
    }
  }
  EXPECT_LT(after, 0.7 * before) << after << " vs " << before;
}

}  // namespace
}  // namespace alignset

#include "storage/profile.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <set>
#include <string>
#include <vector>

#include "storage/set_cache.h"

namespace alignset::storage {
namespace {

FrequencyParams Params() { return {40.0, 3.0, 12.5}; }

TEST(ProfileId, SixteenLowercaseHexDigitsAndStable) {
  const std::string id = ProfileId(Params(), OptimizerOptions{}, 7);
  ASSERT_EQ(id.size(), 16u);
  for (char c : id) EXPECT_TRUE((c >= '0' && c <= '9') || (c >= 'a' && c <= 'f')) << id;
  EXPECT_EQ(ProfileId(Params(), OptimizerOptions{}, 7), id);
  EXPECT_EQ(ProfileId(Params(), OptimizerOptions{}, 7, kAlgorithmVersion), id);
}

TEST(ProfileId, IsAValidKeyProfile) {
  SetKey k;
  k.n = 1024;
  k.dirs = {1, 10, 10};
  k.profile = ProfileId(Params(), OptimizerOptions{}, 1);
  EXPECT_TRUE(ValidateKey(k).ok());
}

// Every parameter that shapes the optimized set must change the id, or the
// cache would return a set made with other parameters.
TEST(ProfileId, EveryParameterChangesTheId) {
  using Mutation = std::function<void(FrequencyParams&, OptimizerOptions&, uint64_t&, int&)>;
  const std::vector<std::pair<std::string, Mutation>> mutations = {
      {"length", [](auto& p, auto&, auto&, auto&) { p.length += 1.0; }},
      {"width", [](auto& p, auto&, auto&, auto&) { p.width += 0.5; }},
      {"radius", [](auto& p, auto&, auto&, auto&) { p.radius *= 1.01; }},
      {"max_iterations", [](auto&, auto& o, auto&, auto&) { o.max_iterations += 1; }},
      {"learning_rate", [](auto&, auto& o, auto&, auto&) { o.learning_rate = 1e-3; }},
      {"sw_weight", [](auto&, auto& o, auto&, auto&) { o.sw_weight = 9.0; }},
      {"weight_exponent", [](auto&, auto& o, auto&, auto&) { o.weighting.exponent += 0.5; }},
      {"warmup_exponent", [](auto&, auto& o, auto&, auto&) { o.warmup_weighting.exponent += 1.0; }},
      {"warmup_fraction", [](auto&, auto& o, auto&, auto&) { o.warmup_fraction = 0.5; }},
      {"final_margin", [](auto&, auto& o, auto&, auto&) { o.final_margin = 0.1; }},
      {"zero_radius", [](auto&, auto& o, auto&, auto&) { o.zero_radius += 1.0; }},
      {"engine_tolerance", [](auto&, auto& o, auto&, auto&) { o.engine_tolerance = 1e-11; }},
      {"stratify_axes", [](auto&, auto& o, auto&, auto&) { o.stratify_axes = !o.stratify_axes; }},
      {"beta1", [](auto&, auto& o, auto&, auto&) { o.beta1 = 0.8; }},
      {"beta2", [](auto&, auto& o, auto&, auto&) { o.beta2 = 0.99; }},
      {"epsilon", [](auto&, auto& o, auto&, auto&) { o.epsilon = 1e-8; }},
      {"divergence_threshold", [](auto&, auto& o, auto&, auto&) { o.divergence_threshold = 0.2; }},
      {"divergence_signal", [](auto&, auto& o, auto&, auto&) { o.divergence_signal = DivergenceSignal::kTotalLoss; }},
      {"revert_divisor", [](auto&, auto& o, auto&, auto&) { o.revert_divisor = 5.0; }},
      {"stall_iterations", [](auto&, auto& o, auto&, auto&) { o.stall_iterations = 100; }},
      {"stall_tolerance", [](auto&, auto& o, auto&, auto&) { o.stall_tolerance = 1e-4; }},
      {"plateau_factor", [](auto&, auto& o, auto&, auto&) { o.plateau_factor = 0.25; }},
      {"anneal_ratio", [](auto&, auto& o, auto&, auto&) { o.anneal_ratio = 0.01; }},
      {"min_learning_rate", [](auto&, auto& o, auto&, auto&) { o.min_learning_rate = 1e-8; }},
      {"warm_budget_fraction", [](auto&, auto& o, auto&, auto&) { o.warm_budget_fraction = 0.5; }},
      {"warm_min_points", [](auto&, auto& o, auto&, auto&) { o.warm_min_points = 1024; }},
      {"warm_warmup_fraction", [](auto&, auto& o, auto&, auto&) { o.warm_warmup_fraction = 0.0; }},
      {"warm_warmup_max_points", [](auto&, auto& o, auto&, auto&) { o.warm_warmup_max_points = 1u << 20; }},
      {"seed", [](auto&, auto&, auto& s, auto&) { s += 1; }},
      {"algorithm_version", [](auto&, auto&, auto&, auto& v) { v += 1; }},
  };
  const std::string base = ProfileId(Params(), OptimizerOptions{}, 7, kAlgorithmVersion);
  std::set<std::string> seen = {base};
  for (const auto& [name, mutate] : mutations) {
    FrequencyParams p = Params();
    OptimizerOptions o;
    uint64_t seed = 7;
    int version = kAlgorithmVersion;
    mutate(p, o, seed, version);
    const std::string id = ProfileId(p, o, seed, version);
    EXPECT_NE(id, base) << name;
    EXPECT_TRUE(seen.insert(id).second) << name << " collides with another mutation";
    // The text names the parameter, so a changed id can be explained.
    EXPECT_NE(ProfileText(p, o, seed, version).find(name + "="), std::string::npos) << name;
  }
}

TEST(ProfileId, OneUlpChangeOfAParameterChangesTheId) {
  OptimizerOptions o;
  o.learning_rate = 0.1;
  OptimizerOptions o2 = o;
  o2.learning_rate = std::nextafter(0.1, 1.0);
  EXPECT_NE(ProfileId(Params(), o, 1), ProfileId(Params(), o2, 1));
  FrequencyParams p2 = Params();
  p2.radius = std::nextafter(p2.radius, 0.0);
  EXPECT_NE(ProfileId(Params(), o, 1), ProfileId(p2, o, 1));
}

TEST(ProfileId, ProgressCadenceDoesNotChangeTheId) {
  OptimizerOptions o;
  OptimizerOptions o2 = o;
  o2.progress_every = o.progress_every + 7;
  EXPECT_EQ(ProfileId(Params(), o, 3), ProfileId(Params(), o2, 3));
}

TEST(ProfileText, CanonicalSerialization) {
  OptimizerOptions o;
  o.max_iterations = 500;
  o.learning_rate = 0.002;
  o.sw_weight = 10.0;
  o.beta1 = 0.9;
  o.beta2 = 0.999;
  o.epsilon = 1e-12;
  o.divergence_threshold = 0.1;
  o.revert_divisor = 10.0;
  o.stall_iterations = 200;
  o.stall_tolerance = 0.001;
  o.plateau_factor = 0.5;
  o.anneal_ratio = 1.0;
  o.min_learning_rate = 1e-7;
  EXPECT_EQ(ProfileText({40.0, 3.0, 12.5}, o, 18446744073709551615ull, 1),
            "alignset-profile-v1;algorithm_version=1;seed=18446744073709551615;length=40;"
            "width=3;radius=12.5;max_iterations=500;learning_rate=0.002;learning_rate_scale=1;sw_weight=10;"
            "weight_exponent=2.5;warmup_exponent=1.5;warmup_fraction=0.7;stratify_axes=1;"
            "zero_radius=3;final_margin=0.4;engine_tolerance=0;beta1=0.9;beta2=0.999;epsilon=1e-12;"
            "divergence_threshold=0.1;divergence_signal=0;revert_divisor=10;"
            "stall_iterations=200;stall_tolerance=0.001;plateau_factor=0.5;anneal_ratio=1;"
            "min_learning_rate=1e-07;warm_budget_fraction=0.13;warm_warmup_fraction=0.5;"
            "warm_pair_learning_rate_scale=2;warm_pair_learning_rate_max_points=4096;"
            "warm_min_points=4096;warm_warmup_max_points=32768;");
}

}  // namespace
}  // namespace alignset::storage

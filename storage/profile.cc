#include "storage/profile.h"

#include <charconv>
#include <cstdio>

#include "core/util/hash.h"
#include "storage/set_cache.h"

namespace alignset::storage {
namespace {

// Adding a field to OptimizerOptions or FrequencyParams changes the struct's
// size; this stops the build until the field is added to ProfileText (or
// deliberately left out there), so a new parameter can never be silently
// missing from the cache key.
static_assert(sizeof(OptimizerOptions) == 224,
              "OptimizerOptions changed: update ProfileText and this size");
static_assert(sizeof(FrequencyParams) == 3 * sizeof(double),
              "FrequencyParams changed: update ProfileText and this size");

template <typename T>
void Field(std::string& out, const char* name, T value) {
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof(buf), value);
  out += name;
  out += '=';
  out.append(buf, r.ptr);
  out += ';';
}

// FNV-1a over the bytes, then the SplitMix64 finalizer so that every output
// bit depends on every input byte (plain FNV-1a mixes its last byte weakly).
uint64_t Hash64(const std::string& text) {
  uint64_t h = 0xcbf29ce484222325ULL;
  for (unsigned char c : text) {
    h ^= c;
    h *= 0x100000001b3ULL;
  }
  return Mix64(h);
}

}  // namespace

std::string ProfileText(const FrequencyParams& params, const OptimizerOptions& o, uint64_t seed,
                        int algorithm_version) {
  std::string t = "alignset-profile-v1;";
  Field(t, "algorithm_version", algorithm_version);
  Field(t, "seed", seed);
  Field(t, "length", params.length);
  Field(t, "width", params.width);
  Field(t, "radius", params.radius);
  Field(t, "max_iterations", o.max_iterations);
  Field(t, "learning_rate", o.learning_rate);
  Field(t, "learning_rate_scale", o.learning_rate_scale);
  Field(t, "sw_weight", o.sw_weight);
  Field(t, "weight_exponent", o.weighting.exponent);
  Field(t, "warmup_exponent", o.warmup_weighting.exponent);
  Field(t, "warmup_fraction", o.warmup_fraction);
  Field(t, "stratify_axes", static_cast<int>(o.stratify_axes));
  Field(t, "zero_radius", o.zero_radius);
  Field(t, "final_margin", o.final_margin);
  Field(t, "engine_tolerance", o.engine_tolerance);
  Field(t, "beta1", o.beta1);
  Field(t, "beta2", o.beta2);
  Field(t, "epsilon", o.epsilon);
  Field(t, "divergence_threshold", o.divergence_threshold);
  Field(t, "divergence_signal", static_cast<int>(o.divergence_signal));
  Field(t, "revert_divisor", o.revert_divisor);
  Field(t, "stall_iterations", o.stall_iterations);
  Field(t, "stall_tolerance", o.stall_tolerance);
  Field(t, "plateau_factor", o.plateau_factor);
  Field(t, "anneal_ratio", o.anneal_ratio);
  Field(t, "min_learning_rate", o.min_learning_rate);
  Field(t, "warm_budget_fraction", o.warm_budget_fraction);
  Field(t, "warm_warmup_fraction", o.warm_warmup_fraction);
  Field(t, "warm_pair_learning_rate_scale", o.warm_pair_learning_rate_scale);
  Field(t, "warm_pair_learning_rate_max_points", o.warm_pair_learning_rate_max_points);
  Field(t, "warm_min_points", o.warm_min_points);
  Field(t, "warm_warmup_max_points", o.warm_warmup_max_points);
  // progress_every is left out on purpose: it only sets how often the
  // callback runs and never changes the optimized set.
  return t;
}

std::string ProfileId(const FrequencyParams& params, const OptimizerOptions& options,
                      uint64_t seed, int algorithm_version) {
  char hex[17];
  std::snprintf(hex, sizeof(hex), "%016llx",
                static_cast<unsigned long long>(
                    Hash64(ProfileText(params, options, seed, algorithm_version))));
  return hex;
}

std::string KeyProfile(uint32_t n, const Construction& construction, const OptimizerOptions& options,
                       uint64_t seed) {
  if (!construction.optimized()) return std::string(construction.profile);
  return ProfileId(DefaultFrequencyParams(n), options, seed);
}

}  // namespace alignset::storage

namespace alignset::storage {

std::string VersionText(const std::string& program, const std::string& release) {
  constexpr uint32_t kHintN = 4096;
  constexpr uint64_t kDefaultSeed = 1;  // alignset-server --seed
  return program + " " + release + "\nalgorithm version " + std::to_string(kAlgorithmVersion) +
         "\nprofile " + ProfileId(DefaultFrequencyParams(kHintN), OptimizerOptions{}, kDefaultSeed) +
         " (default settings, N = " + std::to_string(kHintN) + "; format alignset-profile-v1)";
}

}  // namespace alignset::storage

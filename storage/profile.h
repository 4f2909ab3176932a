#pragma once

#include <cstdint>
#include <string>

#include "core/spectral/frequency_set.h"
#include "core/optimize/optimizer.h"

namespace alignset::storage {

// The canonical text that ProfileId hashes: "name=value;" for every
// parameter in a fixed order, numbers in their shortest round-trip form
// (std::to_chars, so independent of locale), prefixed by a format tag.
// Exposed so that a profile id can be explained (e.g. in logs).
std::string ProfileText(const FrequencyParams& params, const OptimizerOptions& options,
                        uint64_t seed, int algorithm_version);

}  // namespace alignset::storage

namespace alignset::storage {

// The --version text of alignset and alignset-server: the program and its
// release, the algorithm version, and the profile id under which a server with
// default settings caches N = 4096 sets (the same id `alignset stats` shows as
// "profile (N=4096)").
std::string VersionText(const std::string& program, const std::string& release);

}  // namespace alignset::storage

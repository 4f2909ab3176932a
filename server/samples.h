#pragma once

#include <optional>
#include <string>
#include <vector>

#include "core/util/point_set.h"
#include "core/util/status.h"

namespace alignset::server {

// A baseline sampler of the core by name, optionally sheared to `shear_deg`
// (Algorithm 2). Unknown names are INVALID_ARGUMENT listing the known ones.
StatusOr<PointSet> MakeBaselineSamples(const std::string& sampler, uint32_t n, uint64_t seed,
                                       std::optional<double> shear_deg);
std::vector<std::string> BaselineSamplerNames();

}  // namespace alignset::server

#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/util/point_set.h"
#include "core/util/status.h"

namespace alignset {

// The sampler registry: every sampler the project knows, by name, so that the
// CLI, the benches and the service make sets the same way.
struct SamplerInfo {
  std::string name;
  std::string description;  // one line, says which N it accepts
};

// In a fixed order (the order `alignset sample --help` and the comparison
// bench list them).
const std::vector<SamplerInfo>& Samplers();
std::vector<std::string> SamplerNames();

// N points of sampler `name`, deterministic for (name, n, seed), all in
// [0,1)^2. INVALID_ARGUMENT for an unknown name (the message lists the known
// ones) and for an N the sampler cannot honour (the message says why, e.g.
// "jittered needs a square N ... (nearest: 961 or 1024)").
StatusOr<PointSet> Sample(const std::string& name, uint32_t n, uint64_t seed);

}  // namespace alignset

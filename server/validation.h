#pragma once

#include <cstdint>
#include <vector>

#include "core/align/canonical.h"
#include "core/util/status.h"

namespace alignset::server {

// Checks an aligned-set request at the service boundary and maps it onto its
// canonical key. Every refusal is INVALID_ARGUMENT with a message that names
// the offending field and value.
StatusOr<Canonicalization> ValidateAlignedSetRequest(uint32_t n,
                                                     const std::vector<double>& directions_deg,
                                                     uint32_t max_n);
// The same, one direction served on `grid`.
StatusOr<Canonicalization> ValidateAlignedSetRequest(uint32_t n,
                                                     const std::vector<double>& directions_deg,
                                                     uint32_t max_n, AngleGrid grid);

// A request's steps_per_degree: 0 -> `fallback`, 1 or 4 -> that grid,
// anything else INVALID_ARGUMENT.
StatusOr<AngleGrid> ResolveAngleGrid(uint32_t steps_per_degree, AngleGrid fallback);

// N alone (precompute lists, samplers).
Status ValidatePointCount(uint32_t n, uint32_t max_n);

}  // namespace alignset::server

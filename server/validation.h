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

namespace alignset::server {

// The bounds of one GetAlignedSets call: at most this many items, and at most
// this many points over all of them (256 MiB of response).
inline constexpr size_t kMaxBatchItems = 256;
inline constexpr uint64_t kMaxBatchPoints = uint64_t{1} << 24;

// INVALID_ARGUMENT for an empty batch or one beyond the bounds above.
Status ValidateBatchSize(size_t items, uint64_t total_points);

// A realization index: 0 .. kMaxRealization (core/optimize/realization.h).
Status ValidateRealization(uint32_t realization);
// A precompute realization count: 0 (meaning 1) .. kMaxRealization + 1.
Status ValidateRealizationCount(uint32_t count);

}  // namespace alignset::server

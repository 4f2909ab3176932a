#pragma once

// The one rule for how many points a set may have. Every boundary that takes
// an N applies it here, so a bad N is refused in the same words everywhere:
// the command line's options (get, precompute, export, table, optimize), the
// server's requests, the cache's keys and a table file's sections.

#include <cstdint>

#include "core/util/status.h"

namespace alignset {

struct Construction;  // core/optimize/construction.h

// INVALID_ARGUMENT unless kMinPoints <= n <= kMaxPoints
// (core/optimize/optimizer.h): "N = 8 is below the minimum of 16 points"
// (" (missing?)" after it for 0),
// "N = 2000000 is above the maximum of 1048576 points".
Status ValidatePointCount(uint32_t n);
// The range above, then the construction's own size rule
// (Construction::ValidateSize: a net's power of two, a lattice sequence's
// 65536 points).
Status ValidatePointCount(uint32_t n, const Construction& construction);

}  // namespace alignset

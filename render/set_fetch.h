#pragma once

#include <cstdint>
#include <functional>
#include <set>
#include <string>
#include <utility>

#include "render/aligned_sets.h"
#include <alignset/client.h>

#include "core/util/status.h"

namespace alignset::render {

// Progress of a fetch: a stage name, units done of total, and a detail.
using FetchProgressFn =
    std::function<void(const std::string& stage, double done, double total, const std::string& detail)>;

// Asks a running alignset-server for the aligned sets of one N, through the
// public client library only:
//  1. Precompute the one-direction space (46 canonical keys) for N: once per
//     N, resumable, with progress; cached keys cost nothing;
//  2. Precompute the two-direction keys `pairs` need (explicit keys);
//  3. the 180 aligned one-direction sets (every whole degree) and the pairs
//     through the batch call GetAlignedSets (at most kMaxBatchItems a call):
//     cache hits, aligned by the server (swap / invert).
// A failed call comes back as its Status (the server's message).
StatusOr<AlignedSetTable> FetchAlignedSets(ServiceClient& client, uint32_t n,
                                           const std::set<std::pair<int, int>>& pairs,
                                           const FetchProgressFn& progress);

}  // namespace alignset::render

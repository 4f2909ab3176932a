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
//  3. the 46 one-direction keys' sets and the pairs' canonical keys' sets
//     through the batch call GetAlignedSets (at most kMaxBatchItems a call),
//     each asked at the key's own directions, so served as stored.
// The sets are a table of the sampler library (SetTable): a whole
// one-direction section and a two-direction section of the pairs' keys;
// the table aligns them per pixel as the server would have (the same
// swap and mirror). A failed call comes back as its Status (the server's
// message).
//
// construction "lattice" or "tent-lattice": the server's aligned lattices
// instead (SetRequest::construction), so that a render reads the lattices a
// server has chosen and cached instead of searching for them itself (seconds
// to minutes a render at N = 4096): the table holds each key's generator
// (SetInfo::lattice_generator), as AlignedLatticeTable (render/lattice_sets.h)
// would search it here with the server's window. A server that does not
// report generators is FAILED_PRECONDITION.
StatusOr<RenderSets> FetchAlignedSets(ServiceClient& client, uint32_t n,
                                           const std::set<std::pair<int, int>>& pairs,
                                           const FetchProgressFn& progress,
                                           const std::string& construction = "");

}  // namespace alignset::render

#pragma once

#include <cstdint>

#include "core/util/point_set.h"
#include "core/util/status.h"

namespace alignset {

// Progressive multi-jittered (0,2) sequences (Christensen, Kensler & Kilpatrick
// 2018), with the blue-noise variant pmj02bn: the first N points of a
// sequence every power-of-two prefix of which is a (0,m,2)-net in base 2
// (each elementary interval of area 2^-m holds one point), built by doubling:
//   - from 4^k points to 2 * 4^k, each new point goes into the sub-quadrant
//     diagonally opposite its parent's within the parent's square stratum;
//   - from 2 * 4^k to 4^(k+1), the two free sub-quadrants of every stratum
//     get one point each, the first picked at random, in parent order, then
//     the second for every parent (so the prefix 3 * 4^k fills three
//     sub-quadrants of every stratum).
// Within its sub-quadrant a point's remaining binary digits are chosen one at
// a time: a digit whose cell at the new level is already occupied takes the
// other value. That greedy choice never runs into a dead end (every digit has
// at most one occupied alternative: the cell's other point lies in the other
// half of a dyadic group whose digit prefixes are all distinct), so there is
// no rejection loop. Below the net's resolution the point is uniform.
//
// `candidates` > 1 makes pmj02bn: that many valid candidates are drawn for
// each point and the one farthest (toroidally) from all earlier points kept.
// Candidates differ in the odd steps' choice of sub-quadrant and in the
// position below the net's resolution; the (0,2) constraints force every
// other digit (measured: 1.33 distinct net cells per placement over 40
// candidates), so the selection has little room and the result is only
// slightly bluer than pmj02 (mean nearest-neighbour distance within a few
// percent of pmj02's at N = 1024).
// Deterministic for (n, seed, candidates). Any N in [1, 2^20].
StatusOr<PointSet> Pmj02(uint32_t n, uint64_t seed, int candidates);

// The candidate count the registry's "pmj02bn" uses.
inline constexpr int kPmj02bnCandidates = 10;

}  // namespace alignset

#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include "core/spectral/frequency_set.h"
#include "core/spectral/lattice_basis.h"

namespace alignset {

// One piece of a frequency set: the members (indices into K) and the box of
// +-members in a lattice basis, which is where a NUFFT grid evaluates them.
struct FrequencyPiece {
  BasisBox box;
  std::vector<uint32_t> members;
};

// Cost (arbitrary units) of one piece whose box is |w1| <= m1, |w2| <= m2.
using PieceCost = std::function<double(int64_t m1, int64_t m2)>;

// Splits K into pieces whose boxes are small, for the fast engine.
//
// The engine only sees K, not the parameters it was built from, so the
// structure is found from K itself. K (a disk plus thin strips through the
// origin) is cut at a radius r0: frequencies with |v| <= r0 form the central
// piece (identity basis); the rest are grouped by their direction modulo pi
// (gaps in the sorted angles separate the strips), neighbouring groups are
// merged while that lowers the cost, and each group gets the lattice basis
// that makes its box cheapest. Several r0 (multiples of the radius of the
// largest disk K contains) are tried and the cheapest partition kept.
//
// Whatever K is, every member lies in its piece's box and every index of K
// is in exactly one piece, so the result is always correct; only its cost
// depends on K having the expected shape.
std::vector<FrequencyPiece> PartitionFrequencies(const std::vector<Frequency>& k,
                                                 const PieceCost& cost);

// The radius of the largest disk |v| <= r (r integer) whose every lattice
// point but DC is in K up to sign.
int ContainedDiskRadius(const std::vector<Frequency>& k);

}  // namespace alignset

#pragma once

#include <string>

#include "core/util/status.h"

namespace alignset::server {

// How a served set is made (AlignedSetRequest.construction):
// - kOptimized ("" or "optimized", the default): the gradient-descent sets,
//   cached under the server's optimization profile (storage::ProfileId).
// - kLattice ("lattice"): an aligned rank-1 lattice
//   (core/optimize/aligned_lattice.h), its generator chosen for a window of
//   +-kLatticeWindowDeg around the key's exact direction(s), cached under
//   kLatticeProfile. Realization r is Rank1LatticePoints(N, g, r): the seed
//   is the realization number itself (not the server's --seed), so the
//   profile names everything the set depends on.
enum class Construction { kOptimized, kLattice };

// The lattice construction's version (bump it, and kLatticeProfile with it,
// whenever ChooseAlignedLatticeGenerator or Rank1LatticePoints would give a
// different set for the same key) and its window.
inline constexpr int kLatticeAlgorithmVersion = 1;
inline constexpr double kLatticeWindowDeg = 1.0;
// The profile of every lattice key: "lattice", the version, the window in
// degrees. Not a hex id, so no optimizer profile can ever equal it.
inline constexpr const char* kLatticeProfile = "lattice-v1-w1";

// "" or "optimized" -> kOptimized, "lattice" -> kLattice; anything else
// INVALID_ARGUMENT naming the known constructions.
StatusOr<Construction> ParseConstruction(const std::string& name);
// "optimized" or "lattice".
const char* ConstructionName(Construction c);
// The construction a stored key's profile belongs to.
Construction ConstructionOfProfile(const std::string& profile);

}  // namespace alignset::server

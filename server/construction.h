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
// - kNet ("net"): an aligned net (core/optimize/aligned_net.h), a (0,m,2)-net
//   of N = 2^m points whose scrambling is chosen for the key's exact
//   direction(s) +-kNetWindowDeg, cached under kNetProfile; realization r
//   starts its flips from seed r. N must be a power of two.
// - kTentLattice ("tent-lattice"): the aligned rank-1 lattice shifted, then
//   folded by the tent 1 - |2u - 1| (TentLatticePoints), its generator chosen
//   for the folded edges within +-kTentLatticeWindowDeg of the key's exact
//   direction(s), cached under kTentLatticeProfile; realization r is
//   TentLatticePoints(N, g, r), a continuous shift drawn from seed r.
enum class Construction { kOptimized, kLattice, kNet, kTentLattice };

// The lattice construction's version (bump it, and kLatticeProfile with it,
// whenever ChooseAlignedLatticeGenerator or Rank1LatticePoints would give a
// different set for the same key) and its window.
inline constexpr int kLatticeAlgorithmVersion = 2;
inline constexpr double kLatticeWindowDeg = 1.0;
// The profile of every lattice key: "lattice", the version, the window in
// degrees. Not a hex id, so no optimizer profile can ever equal it.
inline constexpr const char* kLatticeProfile = "lattice-v2-w1";
// The net construction's version, window and profile, in the same way.
inline constexpr int kNetAlgorithmVersion = 1;
inline constexpr double kNetWindowDeg = 1.0;
inline constexpr const char* kNetProfile = "net-v1-w1";
// The tent-folded lattice's version and profile (window: the core's
// kTentLatticeWindowDeg, 2 degrees, named in the profile).
inline constexpr int kTentLatticeAlgorithmVersion = 1;
inline constexpr const char* kTentLatticeProfile = "tent-lattice-v1-w2";

// "" or "optimized" -> kOptimized, "lattice" -> kLattice, "net" -> kNet,
// "tent-lattice" -> kTentLattice; anything else INVALID_ARGUMENT naming the
// known constructions.
StatusOr<Construction> ParseConstruction(const std::string& name);
// "optimized", "lattice", "net" or "tent-lattice".
const char* ConstructionName(Construction c);
// INVALID_ARGUMENT when the construction cannot make N points (a net needs
// a power of two from 16 to 65536).
Status ValidateConstructionSize(Construction c, uint32_t n);
// The construction a stored key's profile belongs to.
Construction ConstructionOfProfile(const std::string& profile);

}  // namespace alignset::server

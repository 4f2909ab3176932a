#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "core/util/point_set.h"
#include "core/util/status.h"

namespace alignset {

class LatticeTermCache;  // core/optimize/lattice_term_cache.h

// How a served set is made. Each construction is one value (Constructions()):
// the name the wire, the CLI and a table file use; the profile its keys are
// cached under; the version of its algorithm; the window of directions it is
// chosen for; and how to build its canonical set. Nothing else in the
// project decodes a name or a profile: a caller looks the value up once and
// asks it.
enum class ConstructionKind {
  // The gradient-descent sets (core/optimize/optimizer.h), cached under the
  // server's optimization profile (storage::ProfileId), not a fixed one.
  kOptimized,
  // An aligned rank-1 lattice (core/optimize/aligned_lattice.h), its
  // generator chosen for the window around the key's exact direction(s);
  // realization r is Rank1LatticePoints(N, g, r): the seed is the realization
  // number itself, so the profile names everything the set depends on.
  kLattice,
  // The aligned lattice shifted, then folded by the tent 1 - |2u - 1|
  // (TentLatticePoints), its generator chosen for folded edges; realization
  // r is a continuous shift drawn from seed r.
  kTentLattice,
  // An aligned (0,m,2)-net (core/optimize/aligned_net.h) of N = 2^m points
  // whose scrambling is chosen for the window; realization r starts its
  // flips from seed r.
  kNet,
  // An aligned lattice sequence (core/optimize/lattice_sequence.h): the
  // first N points of one extensible rank-1 lattice whose every power-of-two
  // prefix is an aligned lattice, its generator chosen for all sizes at once,
  // so the set for N is the first N points of the set for any larger N (same
  // directions and realization); realization r is a continuous shift drawn
  // from seed r. N from 16 to 65536.
  kLatticeSequence,
};

// A constructed (not optimized) canonical set.
struct ConstructedSet {
  PointSet points;
  uint32_t lattice_generator = 0;  // a lattice's g of (1, g) / N, a sequence's of phi(i) (1, g); 0 for a net
  int iterations = 0;              // a net's sweeps
  std::string detail;              // one line for the log
};

struct ConstructionContext {
  int threads = 1;  // the generator search's; the set does not depend on it
  // The lattice search's terms kept between keys; the set does not depend on it.
  LatticeTermCache* lattice_terms = nullptr;
};

struct Construction {
  ConstructionKind kind;
  std::string_view name;         // "optimized", "lattice", "tent-lattice", "net", "lattice-sequence"
  std::string_view description;  // "aligned rank-1 lattice", for reports
  // Bump the version, and the profile with it, whenever the construction
  // would give a different set for the same key: the profile is part of the
  // cache key, so a stale set is never served. Not a hex id, so no optimizer
  // profile can ever equal it. Empty for kOptimized.
  int version;
  double window_deg;
  std::string_view profile;

  bool optimized() const { return kind == ConstructionKind::kOptimized; }
  bool lattice() const { return kind == ConstructionKind::kLattice || kind == ConstructionKind::kTentLattice; }
  bool folded() const { return kind == ConstructionKind::kTentLattice; }
  // Its set for N is the first N points of its set for any larger N, and each
  // prefix is a good set of its own: a pixel may stop after any count.
  bool progressive() const { return kind == ConstructionKind::kLatticeSequence; }

  // INVALID_ARGUMENT when it cannot make N points (a net needs a power of
  // two from 16 to 65536, a lattice sequence N from 16 to 65536).
  Status ValidateSize(uint32_t n) const;
  // The canonical set for exact directions `directions_deg` (one or two
  // angles) and realization `seed`. Not for kOptimized (FAILED_PRECONDITION).
  StatusOr<ConstructedSet> Build(uint32_t n, const std::vector<double>& directions_deg, uint64_t seed,
                                 const ConstructionContext& context = {}) const;
};

// Every construction, the default (kOptimized) first.
std::span<const Construction> Constructions();
const Construction& ConstructionOf(ConstructionKind kind);
// "" or a construction's name -> that construction; nullptr for any other.
const Construction* FindConstruction(std::string_view name);
// The construction whose keys a stored profile belongs to: kOptimized's for
// any profile that is no construction's own.
const Construction& ConstructionOfProfile(std::string_view profile);
// "'optimized' (the default, also ''), 'lattice', 'tent-lattice', 'net' and
// 'lattice-sequence'",
// for an error that lists what is accepted.
std::string KnownConstructionNames();

}  // namespace alignset

#pragma once

#include <optional>

#include "core/align/canonical.h"

namespace alignset {

// The warm-start lineage of the canonical key spaces: a fixed forest over the
// keys in which every key but a root has a parent one step away (one
// direction moved by one degree; on the quarter grid, a quarter or half
// degree to the nearest whole degree). A root is optimized from
// Owen-Sobol; any other key continues from its parent's set, aligned onto
// the neighbouring directions, for a short descent (optimizer.h,
// WarmStartOptions). Neighbouring keys' sets differ
// only near the strips that moved, so the short descent reaches the quality
// of a cold one at a fraction of the cost (docs/method.md, "Filling the
// space").
//
// Why a fixed forest: a key's set must be a function of its key alone, not
// of which keys happened to be filled before it. With the parent fixed, a
// key's set is the same whether its parent was read from a cache or
// recomputed on the spot (the optimizer is deterministic and the cache stores
// binary64 exactly), in any fill order, shard or server.
//
// Roots: the one-direction keys 1, 8, ..., 43 (7 roots, depth at most 3,
// mean 1.65); the two-direction keys with 3 phi1 + 4 phi2 = 0 (mod 25), a
// lattice whose diamonds of radius 3 tile the plane, and, where the
// canonical space's edges cut the diamonds, every key still more than 3
// steps from a root, taken in key order (226 roots, depth at most 3, mean
// 2.1). Chains are kept this short because each warm step costs a little
// quality on the integrands the set is not aligned to, and that adds up
// along a chain (docs/results.md, "Filling the space"). Both grids share
// the whole-degree keys and their lineage; a quarter-degree key's parent is
// its nearest whole degree (30.25 and 30.5: 30, 30.75: 31), a step of a
// quarter or half degree.
struct LineageParent {
  CanonicalDirections parent;
  // Align(parent's canonical set, ops) is dark along directions one grid
  // step from the child's own: the start of the child's descent.
  AlignOps ops;
};

// The parent of a canonical key; nullopt for a root or for a key that is
// not canonical (count not 1 or 2, angles out of range).
std::optional<LineageParent> WarmParent(const CanonicalDirections& key);

// Steps from the key to its root (0 for a root); -1 for a non-canonical key.
int LineageDepth(const CanonicalDirections& key);

// The root the key's lineage starts from (the key itself for a root); the
// key unchanged when it is not canonical.
CanonicalDirections LineageRoot(const CanonicalDirections& key);

// The largest depth in a space (count 1 or 2; the quarter grid for count 1).
int MaxLineageDepth(int count, AngleGrid grid = AngleGrid::kWholeDegree);

}  // namespace alignset

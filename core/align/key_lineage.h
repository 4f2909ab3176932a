#pragma once

#include <optional>

#include "core/align/canonical.h"

namespace alignset {

// The warm-start lineage of the canonical key spaces: a fixed forest over the
// keys in which every key but a root has a parent one grid step away (one
// direction moved by one degree, or by a quarter degree on the quarter
// grid). A root is optimized from Owen-Sobol; any other key continues from
// its parent's set, aligned onto the neighbouring directions, for a short
// descent (optimizer.h, WarmStartOptions). Neighbouring keys' sets differ
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
// Roots: the one-direction keys 7, 22, 37 (depth at most 8); the
// two-direction keys with phi1 and phi2 both multiples of 10 (50 roots,
// depth at most 10, mean 5). Both grids share the whole-degree keys and
// their lineage; a quarter-degree key's parent is the neighbour toward the
// nearest whole degree (30.25 and 30.5 toward 30, 30.75 toward 31).
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

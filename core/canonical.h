#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "core/point_set.h"
#include "core/status.h"

namespace alignset {

// The symmetry group of the square that keeps the pair of axes {0°, 90°}:
// identity, swap (x,y) -> (y,x), invert x -> 1 - x, and both. On directions
// (mod 180°) swap maps θ -> 90° - θ, invert maps θ -> 180° - θ, both map
// θ -> θ + 90°. Applied to points in the order: swap first, then invert.
struct AlignOps {
  bool swap = false;
  bool invert = false;
  friend bool operator==(const AlignOps&, const AlignOps&) = default;
};

// A canonical key's directions in whole degrees: one (phi in [0, 45]) for a
// 3-direction set, or an unordered pair (phi1 <= phi2, both in [0, 180)) for a
// 4-direction set. The point count is not part of it.
struct CanonicalDirections {
  int count = 1;  // 1 or 2 arbitrary directions
  int phi1 = 0;
  int phi2 = 0;   // == phi1 and unused when count == 1
  friend bool operator==(const CanonicalDirections&, const CanonicalDirections&) = default;
};

// How a request maps onto the cache: the canonical directions, the group
// element that carries the canonical set onto the request, the whole-degree
// directions actually served (each the nearest whole degree of the request,
// reduced mod 180), and the requested directions as given.
struct Canonicalization {
  CanonicalDirections key;
  AlignOps ops;
  std::vector<int> served_deg;
  std::vector<double> requested_deg;
};

// Any finite real angles (degrees, spectral convention: the edge normal);
// one or two of them. Anything else is INVALID_ARGUMENT.
StatusOr<Canonicalization> Canonicalize(const std::vector<double>& directions_deg);

// The canonical key space: 46 keys for one direction, 4141 for two. The order
// (index <-> key) is part of the contract: batch precompute and sharding use it.
size_t CanonicalKeyCount(int count);
CanonicalDirections CanonicalKeyAt(int count, size_t index);
StatusOr<size_t> CanonicalKeyIndex(const CanonicalDirections& key);

// Applies the group element to points; results stay in [0, 1).
PointSet Align(const PointSet& points, AlignOps ops);
// The inverse element (each element is its own inverse except none; kept for
// clarity at call sites).
AlignOps Inverse(AlignOps ops);
// Direction (degrees mod 180) that `ops` maps `deg` to.
double MapDirection(double deg, AlignOps ops);

std::string ToString(const CanonicalDirections& key);

}  // namespace alignset

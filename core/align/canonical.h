#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "core/util/point_set.h"
#include "core/util/status.h"

namespace alignset {

// An element of the symmetry group of the square that keeps the pair of axes
// {0°, 90°} (the dihedral group of order 8), acting on the torus [0,1)^2.
// Applied to points in the order: swap (x,y) -> (y,x) first, then invert
// x -> 1 - x, then invert y -> 1 - y (the inversions are taken mod 1, so 0
// stays 0).
//
// On directions (mod 180°), swap maps θ -> 90° - θ and each inversion maps
// θ -> 180° - θ; both inversions together are the half turn, which fixes every
// direction. Canonicalize therefore never sets `invert_y`; it exists so that
// every element has a representable inverse: swap-then-invert-x is a quarter
// turn whose inverse is swap-then-invert-y.
struct AlignOps {
  bool swap = false;
  bool invert = false;    // invert x (after the swap)
  bool invert_y = false;  // invert y (after the swap)
  friend bool operator==(const AlignOps&, const AlignOps&) = default;
};

// The grid the one-direction canonical space lives on (the value is the
// number of steps per degree). Whole degrees: 46 keys phi = 0, 1, ..., 45, the
// supplement's Algorithm 1. Quarter degrees: 181 keys phi = 0, 0.25, ...,
// 45, a superset of the whole-degree keys (a whole-degree angle is the same
// key, the same set and the same stored row on both grids). A request is
// served by the nearest grid angle, so at most 1/8° off instead of 1/2°
// (at N = 4096 a 1/2° misalignment costs about 18% of the variance on the
// edge). The two-direction space stays on whole degrees: on quarter degrees
// it would have about 16 x 4141 = 66k keys (docs/method.md, "Canonical keys and alignment").
enum class AngleGrid { kWholeDegree = 1, kQuarterDegree = 4 };

// Steps per degree of a grid (1 or 4).
inline int StepsPerDegree(AngleGrid grid) { return static_cast<int>(grid); }

// A canonical key's directions (spectral convention: each is the normal of
// an integrand edge). One direction (phi in [0, 45]) for a 3-direction set,
// or an unordered pair (phi1 <= phi2, both whole degrees in [0, 180)) for a
// 4-direction set. The point count is not part of it.
//
// phi1 and phi2 are whole degrees; a one-direction key on the quarter-degree
// grid adds phi1_quarter quarter degrees (0..3, 0 at 45): its angle is
// phi1 + phi1_quarter / 4. Every whole-degree key has phi1_quarter 0, so the
// keys of the whole-degree grid are exactly what they always were.
struct CanonicalDirections {
  int count = 1;  // 1 or 2 arbitrary directions
  int phi1 = 0;
  int phi2 = 0;   // == phi1 and unused when count == 1
  int phi1_quarter = 0;  // one direction only: extra quarter degrees, 0..3
  friend bool operator==(const CanonicalDirections&, const CanonicalDirections&) = default;
};

// The key's first and second angle in degrees (phi1 + phi1_quarter / 4 and
// phi2), exact.
double Phi1Degrees(const CanonicalDirections& key);
double Phi2Degrees(const CanonicalDirections& key);

// How a request maps onto the cache: the canonical directions, the group
// element that carries the canonical set onto the request, the directions
// actually served (each the nearest grid angle of the request, reduced mod
// 180, in request order) exactly in served_exact_deg and as the nearest whole
// degree in served_deg (which is exact on the whole-degree grid), and the
// requested directions as given.
//
// Invariant: MapDirection(Phi1Degrees(key), ops) and
// MapDirection(Phi2Degrees(key), ops) are served_exact_deg (as a multiset, for
// two directions; == served_exact_deg[0] for one).
struct Canonicalization {
  CanonicalDirections key;
  AlignOps ops;
  std::vector<int> served_deg;
  std::vector<double> requested_deg;
  std::vector<double> served_exact_deg;
  AngleGrid grid = AngleGrid::kWholeDegree;  // the grid the request was served on
};

// Any finite real angles (degrees, spectral convention: the edge normal); one
// or two of them. Each is reduced mod 180 and rounded to the nearest whole
// degree (ties away from zero; 179.6 -> 180 -> 0). Anything else (no angle,
// three or more, NaN, infinity) is INVALID_ARGUMENT.
//
// One direction (method.md Algorithm 1): served t in [0,45] -> phi = t;
// (45,90] -> 90 - t, swap; (90,135] -> t - 90, swap + invert; (135,180) ->
// 180 - t, invert.
// Two directions: the key is the representative of the request's orbit under
// the group (on directions: identity, swap, invert, swap + invert) whose
// sorted pair (phi1, phi2) is lexicographically smallest; ops is the first
// element in that order (identity, swap, invert, swap + invert) that maps the
// key onto the request.
StatusOr<Canonicalization> Canonicalize(const std::vector<double>& directions_deg);
// The same on `grid`: one direction is rounded to the nearest grid angle
// (ties away from zero, in grid steps) and Algorithm 1 applies unchanged:
// t in [0,45] -> phi = t; (45,90] -> 90 - t, swap; (90,135] -> t - 90,
// swap + invert; (135,180) -> 180 - t, invert. Two directions are always
// served on whole degrees (the result's grid says so).
StatusOr<Canonicalization> Canonicalize(const std::vector<double>& directions_deg, AngleGrid grid);

// The canonical key space: 46 keys for one direction, 4141 for two (the
// whole-degree grid); 181 keys for one direction on the quarter-degree grid.
//
// ORDER CONTRACT (batch precompute and sharding rely on it; never change it):
// keys are sorted ascending by angle (phi1, phi2).
//   count == 1, whole degrees: index i <-> phi = i, for i in [0, 45].
//   count == 2: index i <-> the i-th orbit representative (phi1 <= phi2, the
//               lexicographically smallest sorted pair of its orbit) in
//               ascending (phi1, phi2) order; index 0 is (0, 0), the last
//               index 4140.
//   count == 1, quarter degrees (a separate space with its own order, so
//               that the two above never change): index i <-> phi = i / 4
//               degrees, for i in [0, 180]; the whole-degree key phi = k is
//               index 4k here.
// The one-argument forms are the whole-degree spaces. CanonicalKeyCount of
// anything but 1 or 2 (or 2 on the quarter grid) is 0; CanonicalKeyAt with
// an index out of range returns the default key {1, 0, 0}.
size_t CanonicalKeyCount(int count);
size_t CanonicalKeyCount(int count, AngleGrid grid);
CanonicalDirections CanonicalKeyAt(int count, size_t index);
CanonicalDirections CanonicalKeyAt(int count, size_t index, AngleGrid grid);
// INVALID_ARGUMENT if `key` is not canonical on the grid (wrong count, out of
// range, phi2 != phi1 for one direction, a quarter on the whole-degree grid
// or with two directions, or not its orbit's representative).
StatusOr<size_t> CanonicalKeyIndex(const CanonicalDirections& key);
StatusOr<size_t> CanonicalKeyIndex(const CanonicalDirections& key, AngleGrid grid);

// Applies the group element to points; results stay in [0, 1).
//
// Exactness: the map x -> 1 - x cannot be an exact involution on all doubles
// in [0,1) (below 1/2 there are far more doubles than above), so Align works
// on each coordinate's 53-bit fixed-point value q = round(x * 2^53) mod 2^53,
// inverting as q -> (2^53 - q) mod 2^53, and returns q * 2^-53 exactly.
// Coordinates already on that grid (every coordinate >= 1/2, every multiple
// of 2^-53 such as Owen-Sobol's 2^-32 digits or Pcg32::NextDouble) pass
// unchanged through the identity; others (only possible below 1/2) move by
// at most 2^-54, far below anything a spectrum up to |v| ~ 10^3 can see. On the grid the group acts exactly: Align(Align(p, a), b) ==
// Align(p, Compose(a, b)) and Align(Align(p, a), Inverse(a)) == Align(p, {})
// bit for bit. Inputs outside [0,1) are wrapped first.
PointSet Align(const PointSet& points, AlignOps ops);
Point2 AlignPoint(Point2 p, AlignOps ops);

// The inverse element: (swap, ix, iy) -> (swap, iy, ix) when swapping,
// otherwise the element itself.
AlignOps Inverse(AlignOps ops);
// The element equal to applying `first`, then `second`.
AlignOps Compose(AlignOps first, AlignOps second);
// Direction (degrees, reduced to [0, 180)) that `ops` maps `deg` to.
double MapDirection(double deg, AlignOps ops);

// "phi=30" for one direction ("phi=30.25" off whole degrees), "phi=10,75"
// for two.
std::string ToString(const CanonicalDirections& key);
// A grid angle in degrees as text: "30", "30.25", "30.5", "30.75".
std::string FormatGridAngle(double deg);
// "identity", or the parts joined by '+': "swap+invert_x".
std::string ToString(AlignOps ops);

}  // namespace alignset

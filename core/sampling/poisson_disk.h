#pragma once

#include <cstdint>

#include "core/util/point_set.h"
#include "core/util/status.h"

namespace alignset {

// Poisson-disk sets on the torus (distances wrap, like the Cranley-Patterson
// rotation that evaluates them). Both return exactly N points whose pairwise
// toroidal distance is at least *radius (when radius is given).
//
// Radii are stated relative to r_max(N) = sqrt(2 / (sqrt(3) N)), the spacing
// of N points in a hexagonal packing of the unit torus.

// Dart throwing: uniform candidates, each kept if no earlier
// point lies within r. Starts at r = 0.75 r_max, close to the jamming limit
// of random sequential addition (~0.78 r_max); whenever 4096 darts in a row
// miss, r shrinks by 2 % (points already placed stay valid).
StatusOr<PointSet> PoissonDiskDartThrowing(uint32_t n, uint64_t seed, double* radius = nullptr);

// Bridson 2007: grows the set from a random seed point, trying k = 30 points
// in the annulus [r, 2r] around active points, until none is active. The
// count for a radius is not known beforehand: the radius is tuned (at most a
// few runs) until a run yields N or slightly more points, and the excess is
// dropped at random (dropping keeps the minimum distance).
StatusOr<PointSet> PoissonDiskBridson(uint32_t n, uint64_t seed, double* radius = nullptr);

double HexagonalSpacing(uint32_t n);

}  // namespace alignset

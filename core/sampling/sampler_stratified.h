#pragma once

#include <cstdint>

#include "core/util/point_set.h"
#include "core/util/status.h"

namespace alignset {

// The classic stratified samplers (grid, jitter, n-rooks, multi-jittered),
// each deterministic for (n, seed). Those that need a square N refuse any
// other N with INVALID_ARGUMENT naming the nearest squares.

// White noise: N independent uniform points.
StatusOr<PointSet> RandomPoints(uint32_t n, uint64_t seed);

// The centres of an m x m grid of strata (N = m^2). No randomness.
StatusOr<PointSet> RegularGrid(uint32_t n);

// Uniform jitter: the regular grid shifted by one random offset
// inside a stratum, shared by every point (N = m^2).
StatusOr<PointSet> UniformJitter(uint32_t n, uint64_t seed);

// Random jitter, the usual "jittered" sampler: one independent uniform point
// in each of m x m strata (N = m^2).
StatusOr<PointSet> Jittered(uint32_t n, uint64_t seed);

// N-rooks (Latin hypercube): one point in each of N columns and N rows.
StatusOr<PointSet> NRooks(uint32_t n, uint64_t seed);

// Multi-jittered (Chiu, Shirley & Wang 1994) and correlated multi-jittered
// (Kensler 2013) on an m x k grid of cells with m * k = N (the most square
// factorization, see MultiJitterShape): one point per cell and at the same
// time one point in each of N columns and N rows. Correlated: every column
// shares one shuffle of its sub-columns and every row one of its sub-rows.
StatusOr<PointSet> MultiJittered(uint32_t n, uint64_t seed);
StatusOr<PointSet> CorrelatedMultiJittered(uint32_t n, uint64_t seed);

// The cell grid used for N: m columns and k rows, m <= k, m * k = N, m the
// largest divisor of N not above sqrt(N) (a prime N degenerates to 1 x N).
void MultiJitterShape(uint32_t n, uint32_t* columns, uint32_t* rows);

}  // namespace alignset

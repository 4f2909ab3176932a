#pragma once

#include <cstdint>

#include "core/util/point_set.h"
#include "core/util/status.h"

namespace alignset {

// A rank-1 lattice s_i = frac(i * (1, g) / N + shift) (the screen-space
// sampler, screen_space_rank1.h, uses the same form per pixel), with a Cranley-Patterson shift drawn from the seed.
// The generator g is F_(k-1) when N is the Fibonacci number F_k >= 3 (the
// Fibonacci lattice), otherwise the Korobov generator with the largest
// minimum distance between points (ties: smallest g), searched over every g
// coprime to N in [1, N/2]. Coprime g makes the set an N-rooks set too: one
// point in each of N columns and N rows. Any N in [1, 2^20].
StatusOr<PointSet> Rank1Lattice(uint32_t n, uint64_t seed);

uint32_t Rank1Generator(uint32_t n);

// The minimum toroidal distance between two points of the unshifted lattice
// with generator g, times N (the length of its shortest nonzero vector in
// the integer lattice spanned by (1, g) and (0, N)). Found by Lagrange-Gauss
// reduction.
double Rank1MinDistanceTimesN(uint32_t n, uint32_t g);

bool IsFibonacci(uint32_t n, uint32_t* previous);

// g^-1 mod N for g coprime to N (the extended Euclidean algorithm): the
// generator of the lattice (1, g) with its axes swapped.
uint32_t Rank1InverseMod(uint32_t g, uint32_t n);

}  // namespace alignset

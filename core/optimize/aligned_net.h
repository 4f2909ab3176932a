#pragma once

#include <cstdint>
#include <vector>

#include "core/util/point_set.h"
#include "core/util/status.h"

namespace alignset {

// An aligned net: a (0,m,2)-net of N = 2^m points whose scrambling is
// chosen for step edges with normals near the requested directions.
//
// Why a net: Owen-scrambled Sobol keeps every elementary interval of area
// 1/N at one point, which keeps the hyperbolic cross |h_x h_y| < N of its
// spectrum dark and integrates smooth, non-periodic functions at N^-1.5 and
// better; the optimized sets and the lattices do not (docs/results.md). A
// scramble is a binary tree of flips per coordinate (a flip at a node
// toggles one digit of every point below it), and every choice of flips is
// again a net, so the flips can be optimized for an edge without losing the
// net (Ahmed and Wonka, "Optimizing dyadic nets", 2021, did this for blue
// noise).
//
// How: the points are the first N Sobol points, each digit scrambled by the
// flip tree and placed at the centre of its cell (a centred net: one point
// in the middle of each column and row, so the axis frequencies below N are
// exactly dark). The objective is a truncated exact Cranley-Patterson
// variance sum_h w(h) |S(h)|^2 over the frequencies h with the largest
// weights w(h) = mean |f^(h)|^2 of a family of step edges (each direction
// within +-window_deg, three offsets), in a half disk of radius
// radius_factor * sqrt(N) (at most max_frequencies of them), plus a smooth
// guard on the lowest frequencies (see smooth_weight), each part relative to
// its value at the start. The flips start
// from a random scramble drawn from `seed` and are improved greedily, node
// by node from the root, for `sweeps` passes or until none helps.
// Deterministic in (N, directions, seed, options).
struct AlignedNetOptions {
  double window_deg = 1.0;
  double radius_factor = 8.0;
  int max_frequencies = 3000;
  int sweeps = 4;
  // The smooth guard's weight against the edges' (each relative to the
  // random scramble's): the low frequencies of non-periodic smooth
  // functions (a corner term and a centred Gaussian).
  double smooth_weight = 1.0;
};

struct AlignedNetResult {
  PointSet points;
  double start_objective = 0.0;  // of the random scramble (1 + smooth_weight by construction)
  double objective = 0.0;        // after the flips (lower is better)
  int flips = 0;                 // flips accepted
  int sweeps = 0;                // passes run
  int frequencies = 0;
};

// INVALID_ARGUMENT for N not a power of two in [16, 2^16], no direction or
// more than 8, a direction that is not finite, or options out of range.
StatusOr<AlignedNetResult> AlignedNet(uint32_t n, const std::vector<double>& directions_deg,
                                      uint64_t seed, const AlignedNetOptions& options = {});

}  // namespace alignset

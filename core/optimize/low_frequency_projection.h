#pragma once

#include <vector>

#include "core/spectral/frequency_set.h"
#include "core/util/point_set.h"

namespace alignset {

// The frequencies 0 < |v| <= radius, one of each +-v pair.
std::vector<Frequency> LowFrequencies(double radius);

// Moves the points as little as possible so that F(v) = sum_j
// exp(-2 pi i v.s_j) vanishes at every v in `frequencies`: Gauss-Newton on
// the 2|V| real constraints, each step the least-norm displacement that
// zeroes their linearization (delta = -J^T (J J^T)^-1 r). A set with F = 0
// at |v| <= r integrates every trigonometric polynomial of degree <= r
// exactly, under any Cranley-Patterson shift: the variance of a smooth
// integrand then starts at |v| > r, where its coefficients are small.
//
// Why a projection and not more weight in the loss: the lowest frequencies
// must reach P(v) ~ 1/N^2 (where Owen-scrambled Sobol is), eight orders of
// magnitude below the rest of K at N = 65536; an Adam step, a fixed fraction
// of a stratum per coordinate, cannot resolve that, while the least-norm
// step moves each point by ~|F| / (2 pi |v| N), a tenth of a stratum.
//
// Returns max over V of |F(v)|^2 / N (the periodogram) after the last step.
double ProjectLowFrequencies(PointSet* points, const std::vector<Frequency>& frequencies,
                             int iterations = 3);

}  // namespace alignset

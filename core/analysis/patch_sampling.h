#pragma once

#include <cstdint>
#include <functional>

#include "core/analysis/patch_spectrum.h"

namespace alignset {

using Integrand2 = std::function<double(const Point2&)>;

// f at the cell centres of a W x H grid (GridPatch's convention).
GridPatch PointSampledGrid(const Integrand2& f, int width, int height);

// Each cell's value the mean of `spp` uniform random samples in the cell
// (a noisy estimate of the cell average), from `seed`.
GridPatch RandomSampledGrid(const Integrand2& f, int width, int height, int spp, uint64_t seed);

// `count` uniform random samples over [0,1)^2, from `seed`.
SampledPatch RandomSamples(const Integrand2& f, int count, uint64_t seed);

}  // namespace alignset

#pragma once

#include <cstdint>
#include <vector>

#include "core/analysis/integrand.h"
#include "core/analysis/variance.h"
#include "core/spectral/spectral_engine.h"
#include "core/util/point_set.h"

namespace alignset {

// The variance of a sampler's estimator of `f` at one N, from several of its
// sets (seeds, scrambles), in the three ways the convergence plots use.
//
// Cranley-Patterson rotated, by Monte Carlo: the mean over the sets of each
// set's CP variance (`shifts` shifts from `seed`, the same for every set).
// The standard error is that of the mean over sets when there are several
// (the spread between sets dominates), else the set's own.
VarianceEstimate CpVarianceOverSets(const std::vector<PointSet>& sets, const Integrand& f,
                                    int shifts, uint64_t seed);

// Cranley-Patterson rotated, exactly by Eq. 18 (exact_variance.h), summed to
// |v| <= radius with the Parseval tail estimate; the mean over the sets.
// `shifts` of the result is 0.
VarianceEstimate ExactCpVarianceOverSets(const std::vector<PointSet>& sets, const Integrand& f,
                                         int radius, SpectralEngine& engine);

// Without homogenization: the mean squared error of the plain estimates
// (1/N) sum f(s_j) of the sets against the exact integral, i.e. the variance
// the sampler's own randomization (scrambling, jitter) leaves. Meaningful for
// unbiased randomized samplers only, and it needs many sets (64 or more).
VarianceEstimate PlainVarianceOverSets(const std::vector<PointSet>& sets, const Integrand& f);

}  // namespace alignset

#pragma once

#include <cstdint>
#include <functional>

#include "core/util/point_set.h"

namespace alignset {

struct VarianceEstimate {
  double variance = 0.0;   // mean squared error of the estimates
  double std_error = 0.0;  // standard error of `variance` itself
  int shifts = 0;
};

// The variance of the Cranley-Patterson-rotated estimator
// I = (1/N) sum f((s_j + u) mod 1) over `shifts` uniform shifts u (drawn from
// `seed`, so two sets compared with one seed see the same shifts). The
// estimator is unbiased, so its variance is its mean squared error against
// `reference` (the exact integral).
VarianceEstimate CranleyPattersonVariance(const PointSet& points,
                                          const std::function<double(const Point2&)>& f,
                                          double reference, int shifts, uint64_t seed);

// The mean CP variance over a family of `edges` parallel step edges with
// normal `normal_deg` (core/analysis/step_integrand.h), at offsets spread evenly over
// [-1/4, 1/4] along the normal, all with the same shifts. One edge is the
// edge through the centre. Averaging over edge positions keeps the figure a
// property of the set rather than of one lucky or unlucky edge.
VarianceEstimate StepEdgeVariance(const PointSet& points, double normal_deg, int edges, int shifts,
                                  uint64_t seed);

// Least-squares slope of log(variance) against log(N).
double LogLogSlope(const std::vector<double>& n, const std::vector<double>& variance);

}  // namespace alignset

#pragma once

#include <cstdint>
#include <functional>

#include "core/point_set.h"

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

// Least-squares slope of log(variance) against log(N).
double LogLogSlope(const std::vector<double>& n, const std::vector<double>& variance);

}  // namespace alignset

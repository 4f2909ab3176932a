#include "core/analysis/variance.h"

#include <cmath>
#include <vector>

#include "core/util/hash.h"
#include "core/analysis/step_integrand.h"

namespace alignset {

VarianceEstimate CranleyPattersonVariance(const PointSet& points,
                                          const std::function<double(const Point2&)>& f,
                                          double reference, int shifts, uint64_t seed) {
  VarianceEstimate out;
  out.shifts = shifts;
  if (points.empty() || shifts <= 0) return out;
  Pcg32 rng(seed);
  double sum = 0.0, sum_sq = 0.0;
  const double inv_n = 1.0 / static_cast<double>(points.size());
  for (int s = 0; s < shifts; ++s) {
    const double ux = rng.NextDouble(), uy = rng.NextDouble();
    double acc = 0.0;
    for (const Point2& p : points) acc += f({Wrap01(p.x + ux), Wrap01(p.y + uy)});
    const double err = acc * inv_n - reference;
    sum += err * err;
    sum_sq += err * err * err * err;
  }
  const double m = sum / shifts;
  out.variance = m;
  const double var_of_sq = std::max(0.0, sum_sq / shifts - m * m);
  out.std_error = std::sqrt(var_of_sq / shifts);
  return out;
}

VarianceEstimate StepEdgeVariance(const PointSet& points, double normal_deg, int edges, int shifts,
                                  uint64_t seed) {
  VarianceEstimate out;
  out.shifts = shifts;
  if (edges < 1) return out;
  double se2 = 0.0;
  for (int e = 0; e < edges; ++e) {
    const double offset = edges == 1 ? 0.0 : 0.5 * (e + 0.5) / edges - 0.25;
    const StepIntegrand f(normal_deg, offset);
    const VarianceEstimate v = CranleyPattersonVariance(points, f, f.Integral(), shifts, seed);
    out.variance += v.variance / edges;
    se2 += v.std_error * v.std_error;
  }
  out.std_error = std::sqrt(se2) / edges;
  return out;
}

double LogLogSlope(const std::vector<double>& n, const std::vector<double>& variance) {
  const size_t k = std::min(n.size(), variance.size());
  if (k < 2) return 0.0;
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (size_t i = 0; i < k; ++i) {
    const double x = std::log(n[i]), y = std::log(variance[i]);
    sx += x;
    sy += y;
    sxx += x * x;
    sxy += x * y;
  }
  const double d = static_cast<double>(k) * sxx - sx * sx;
  return d == 0.0 ? 0.0 : (static_cast<double>(k) * sxy - sx * sy) / d;
}

}  // namespace alignset

#include "core/analysis/convergence.h"

#include <cmath>

#include "core/analysis/exact_variance.h"

namespace alignset {
namespace {

// Mean of `values` and the standard error of that mean.
VarianceEstimate MeanOf(const std::vector<double>& values) {
  VarianceEstimate out;
  const double m = static_cast<double>(values.size());
  double sum = 0.0;
  for (double v : values) sum += v;
  out.variance = sum / m;
  if (values.size() > 1) {
    double ss = 0.0;
    for (double v : values) ss += (v - out.variance) * (v - out.variance);
    out.std_error = std::sqrt(ss / (m - 1.0) / m);
  }
  return out;
}

}  // namespace

VarianceEstimate CpVarianceOverSets(const std::vector<PointSet>& sets, const Integrand& f,
                                    int shifts, uint64_t seed) {
  std::vector<double> per_set;
  double own_error = 0.0;
  for (const PointSet& s : sets) {
    const VarianceEstimate v = CranleyPattersonVariance(
        s, [&f](const Point2& p) { return f.Value(p); }, f.Integral(), shifts, seed);
    per_set.push_back(v.variance);
    own_error = v.std_error;
  }
  VarianceEstimate out = MeanOf(per_set);
  if (sets.size() == 1) out.std_error = own_error;
  out.shifts = shifts;
  return out;
}

VarianceEstimate ExactCpVarianceOverSets(const std::vector<PointSet>& sets, const Integrand& f,
                                         int radius, SpectralEngine& engine) {
  const IntegrandEnergy energy = ComputeIntegrandEnergy(radius, f);
  std::vector<double> per_set;
  for (const PointSet& s : sets) {
    per_set.push_back(ExactCpVariance(ComputeDiskSpectrum(s, radius, engine), energy).variance);
  }
  return MeanOf(per_set);
}

VarianceEstimate PlainVarianceOverSets(const std::vector<PointSet>& sets, const Integrand& f) {
  std::vector<double> squared_errors;
  const double reference = f.Integral();
  for (const PointSet& s : sets) {
    double sum = 0.0;
    for (const Point2& p : s) sum += f.Value(p);
    const double e = sum / static_cast<double>(s.size()) - reference;
    squared_errors.push_back(e * e);
  }
  return MeanOf(squared_errors);
}

}  // namespace alignset

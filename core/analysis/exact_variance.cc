#include "core/analysis/exact_variance.h"

#include <algorithm>

namespace alignset {

DiskSpectrum ComputeDiskSpectrum(const PointSet& points, int radius, SpectralEngine& engine) {
  DiskSpectrum out;
  out.radius = radius;
  out.point_count = points.size();
  // No strip directions: BuildFrequencySet gives the disk alone.
  out.frequencies = BuildFrequencySet({1.0, 1.0, static_cast<double>(radius)}, {});
  engine.SetFrequencies(out.frequencies);
  SpectrumEvaluation eval;
  engine.Evaluate(points, false, &eval);
  out.f = std::move(eval.spectrum);
  return out;
}

ExactVariance ExactCpVariance(const DiskSpectrum& spectrum, const Integrand& f) {
  ExactVariance out;
  out.radius = spectrum.radius;
  const double n = static_cast<double>(std::max<size_t>(spectrum.point_count, 1));
  double head = 0.0, energy = 0.0;
  for (size_t i = 0; i < spectrum.frequencies.size(); ++i) {
    const Frequency& v = spectrum.frequencies[i];
    const double coefficient = std::norm(f.Fourier(v.a, v.b));
    head += std::norm(spectrum.f[i]) * coefficient;
    energy += coefficient;
  }
  out.head = 2.0 * head / (n * n);
  const double mean = f.Integral();
  const double total = f.SquareIntegral() - mean * mean;
  out.tail_energy = std::max(0.0, total - 2.0 * energy);
  out.tail_estimate = out.tail_energy / n;
  out.tail_bound = out.tail_energy;
  out.variance = out.head + out.tail_estimate;
  return out;
}

}  // namespace alignset

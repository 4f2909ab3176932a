#include "core/analysis/exact_variance.h"

#include <algorithm>
#include <cassert>

namespace alignset {

namespace {

// The half disk 0 < |v| <= radius: no strip directions, the disk alone.
std::vector<Frequency> DiskFrequencies(int radius) {
  return BuildFrequencySet({1.0, 1.0, static_cast<double>(radius)}, {});
}

}  // namespace

DiskSpectrum ComputeDiskSpectrum(const PointSet& points, int radius, SpectralEngine& engine) {
  DiskSpectrum out;
  out.radius = radius;
  out.point_count = points.size();
  out.frequencies = DiskFrequencies(radius);
  engine.SetFrequencies(out.frequencies);
  SpectrumEvaluation eval;
  engine.Evaluate(points, false, &eval);
  out.f = std::move(eval.spectrum);
  return out;
}

IntegrandEnergy ComputeIntegrandEnergy(int radius, const Integrand& f) {
  IntegrandEnergy out;
  out.radius = radius;
  for (const Frequency& v : DiskFrequencies(radius)) {
    out.energy.push_back(std::norm(f.Fourier(v.a, v.b)));
    out.energy_sum += out.energy.back();
  }
  const double mean = f.Integral();
  out.variance = f.SquareIntegral() - mean * mean;
  return out;
}

ExactVariance ExactCpVariance(const DiskSpectrum& spectrum, const IntegrandEnergy& f) {
  assert(f.radius == spectrum.radius && f.energy.size() == spectrum.f.size());
  ExactVariance out;
  out.radius = spectrum.radius;
  const double n = static_cast<double>(std::max<size_t>(spectrum.point_count, 1));
  double head = 0.0;
  for (size_t i = 0; i < spectrum.f.size(); ++i) head += std::norm(spectrum.f[i]) * f.energy[i];
  out.head = 2.0 * head / (n * n);
  out.tail_energy = std::max(0.0, f.variance - 2.0 * f.energy_sum);
  out.tail_estimate = out.tail_energy / n;
  out.tail_bound = out.tail_energy;
  out.variance = out.head + out.tail_estimate;
  return out;
}

ExactVariance ExactCpVariance(const DiskSpectrum& spectrum, const Integrand& f) {
  return ExactCpVariance(spectrum, ComputeIntegrandEnergy(spectrum.radius, f));
}

}  // namespace alignset

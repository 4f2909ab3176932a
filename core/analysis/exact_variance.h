#pragma once

#include <complex>
#include <cstddef>
#include <vector>

#include "core/analysis/integrand.h"
#include "core/spectral/frequency_set.h"
#include "core/spectral/spectral_engine.h"
#include "core/util/point_set.h"

namespace alignset {

// F(v) = sum_j exp(-2 pi i v.s_j) of one point set over the half disk
// 0 < |v| <= radius (one of each +-v pair), computed once and shared by the
// exact variances of any number of integrands.
struct DiskSpectrum {
  int radius = 0;
  size_t point_count = 0;
  std::vector<Frequency> frequencies;
  std::vector<std::complex<double>> f;
};
DiskSpectrum ComputeDiskSpectrum(const PointSet& points, int radius, SpectralEngine& engine);

// The variance of the Cranley-Patterson-rotated estimator by supplement
// Eq. 18, Var = sum over v != 0 of P_S(v) |f^(v)|^2 / N, truncated to
// |v| <= radius:
//   head          = 2 sum over the half disk of |F(v)|^2 |f^(v)|^2 / N^2 (exact);
//   tail_energy   = sum over |v| > radius of |f^(v)|^2
//                 = (integral f^2 - (integral f)^2) - 2 sum over the half disk
//                   of |f^(v)|^2, exactly, by Parseval;
//   the tail of the variance, sum over |v| > radius of P_S(v) |f^(v)|^2 / N,
//   lies in [0, tail_energy] (P_S <= N), and equals tail_energy / N when the
//   periodogram averages 1 beyond the radius (white noise, jittered and
//   optimized sets; not lattices, whose P_S reaches N on the dual lattice).
// `variance` = head + tail_estimate, with tail_estimate = tail_energy / N.
// Callers judge the truncation by tail_estimate / variance.
struct ExactVariance {
  double variance = 0.0;
  double head = 0.0;
  double tail_energy = 0.0;
  double tail_estimate = 0.0;
  double tail_bound = 0.0;
  int radius = 0;
};
ExactVariance ExactCpVariance(const DiskSpectrum& spectrum, const Integrand& f);

// The part of that sum that depends on the integrand alone, |f^(v)|^2 over
// the half disk of a radius (DiskSpectrum's frequencies, in its order), and
// f's variance: computed once for any number of sets, where f^ is the
// costly side (a polygon's coefficients against one NUFFT per set).
struct IntegrandEnergy {
  int radius = 0;
  std::vector<double> energy;  // |f^(v)|^2
  double energy_sum = 0.0;     // sum of `energy`
  double variance = 0.0;       // integral f^2 - (integral f)^2
};
IntegrandEnergy ComputeIntegrandEnergy(int radius, const Integrand& f);
// The same variance from a precomputed energy of the spectrum's radius.
ExactVariance ExactCpVariance(const DiskSpectrum& spectrum, const IntegrandEnergy& f);

}  // namespace alignset

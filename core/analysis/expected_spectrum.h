#pragma once

#include <cstddef>
#include <vector>

#include "core/spectral/spectral_engine.h"
#include "core/util/point_set.h"
#include "core/util/status.h"

namespace alignset {

// The expected power spectrum <P_S(v)> of a sampler, estimated as the mean
// periodogram P_S(v) = |sum_j exp(-2 pi i v.s_j)|^2 / N of several of its
// sets (seeds, scrambles, realizations) at every integer frequency of the
// box |a|, |b| <= M (the talk's vocabulary: white noise is 1, DC left out).
//
// A Cranley-Patterson shift u multiplies F(v) by exp(-2 pi i v.u), so the
// periodogram of one set is the same under every CP shift: averaging over CP
// shifts adds nothing, and the expectation over the sampler's randomness
// comes from several sets.
struct ExpectedSpectrum {
  int max_frequency = 0;  // M
  size_t point_count = 0;
  int set_count = 0;
  // (2M + 1)^2 values, index (a + M) (2M + 1) + (b + M); the DC entry is 0.
  std::vector<double> power;
  double At(int a, int b) const {
    const int w = 2 * max_frequency + 1;
    return power[static_cast<size_t>(a + max_frequency) * w + (b + max_frequency)];
  }
};

// All sets must have the same N (INVALID_ARGUMENT otherwise); M in [1, 1024].
StatusOr<ExpectedSpectrum> ComputeExpectedSpectrum(const std::vector<PointSet>& sets,
                                                   int max_frequency, SpectralEngine& engine);

// Mean power over the annulus round(|v|) = r, r = 0 .. M (entry 0 is 0: DC);
// only frequencies with |v| <= M + 1/2 count, so every annulus is whole.
std::vector<double> RadialProfile(const ExpectedSpectrum& s);

// Energy along a direction against |v|: entry t (t = 0 .. M) is the mean
// power of the frequencies within 1/2 of the line through 0 along `deg`
// (|v.d_perp| <= 1/2) whose projection rounds to +-t (entry 0 is 0: DC; an
// entry no integer frequency falls on, as happens along most angles, is NaN).
// This is the profile a strip of width 1 suppresses.
std::vector<double> DirectionalProfile(const ExpectedSpectrum& s, double deg);

// Mean power per angle over [0°, 180°) in `bins` equal bins, for the
// frequencies with r_min <= |v| <= M (each v and -v fall in one bin: P is
// even). A bin that holds no frequency is 0.
std::vector<double> AngularProfile(const ExpectedSpectrum& s, int bins, double r_min);

}  // namespace alignset

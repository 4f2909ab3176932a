#pragma once

#include <vector>

#include "core/spectral/frequency_set.h"

namespace alignset {

// How the spectrum loss weighs the frequencies of K:
//   L_Spec = (1/|K|) sum over v in K of w(v) P_S(v),
//   w(v)  ~ (r_min / |v|)^exponent, times `low_boost` where |v| <= low_radius,
// normalised to mean 1 over K (so exponent 0 and boost 1 give the flat mean
// of the supplement). Eq. 18 says a set's variance on f is
// sum P_S(v) |f^(v)|^2 / N: weights that fall with |v| shape the loss like
// the integrands' spectra, which fall like |v|^-2 along an edge's normal and
// faster for smooth functions.
struct SpectrumWeighting {
  double exponent = 0.0;
  // Members of an arbitrary direction's strip beyond the disk radius R fall
  // like |v|^-strip_exponent instead (continuous at R); < 0: `exponent`.
  double strip_exponent = -1.0;
  // ... and are multiplied by strip_scale (the jump at R sets how much of
  // the loss the arbitrary strips get against the disk and the axes).
  double strip_scale = 1.0;
  double low_radius = 0.0;
  double low_boost = 1.0;
  bool flat() const {
    return exponent == 0.0 && strip_exponent <= 0.0 && strip_scale == 1.0 &&
           (low_boost == 1.0 || low_radius <= 0.0);
  }
  friend bool operator==(const SpectrumWeighting&, const SpectrumWeighting&) = default;
};

// w over K in K's order; empty when the weighting is flat (the engines'
// unweighted path, bit-identical to the supplement's mean). `params` and the
// arbitrary (non-axis) directions tell which members lie in whose strip.
std::vector<double> SpectrumLossWeights(const std::vector<Frequency>& k,
                                        const SpectrumWeighting& weighting,
                                        const FrequencyParams& params,
                                        const std::vector<double>& arbitrary_directions);

}  // namespace alignset

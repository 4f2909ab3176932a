#pragma once

#include <vector>

#include "core/spectral/frequency_set.h"

namespace alignset {

// How the spectrum loss weighs the frequencies of K:
//   L_Spec = (1/|K|) sum over v in K of w(v) P_S(v),  w(v) ~ (r_min / |v|)^exponent,
// normalised to mean 1 over K (exponent 0 is the flat mean of the supplement).
// Eq. 18 says a set's variance on f is sum P_S(v) |f^(v)|^2 / N: weights that
// fall with |v| shape the loss like the integrands' spectra, which fall like
// |v|^-2 along an edge's normal and faster for smooth functions. Measured
// alternatives (a separate exponent or scale for the arbitrary strips, an
// extra boost inside a small radius) did not beat the single exponent
// (docs/method.md, "The low-frequency floor") and were removed.
struct SpectrumWeighting {
  double exponent = 0.0;
  bool flat() const { return exponent == 0.0; }
  friend bool operator==(const SpectrumWeighting&, const SpectrumWeighting&) = default;
};

// w over K in K's order; empty when the weighting is flat (the engines'
// unweighted path, bit-identical to the supplement's mean).
std::vector<double> SpectrumLossWeights(const std::vector<Frequency>& k,
                                        const SpectrumWeighting& weighting);

}  // namespace alignset

#include "core/optimize/spectrum_weights.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace alignset {

std::vector<double> SpectrumLossWeights(const std::vector<Frequency>& k,
                                        const SpectrumWeighting& weighting) {
  if (weighting.flat() || k.empty()) return {};
  double r_min = std::numeric_limits<double>::infinity();
  for (const Frequency& v : k) r_min = std::min(r_min, std::hypot(v.a, v.b));
  std::vector<double> w(k.size());
  double sum = 0.0;
  for (size_t i = 0; i < k.size(); ++i) {
    w[i] = std::pow(r_min / std::hypot(k[i].a, k[i].b), weighting.exponent);
    sum += w[i];
  }
  const double scale = static_cast<double>(k.size()) / sum;
  for (double& wi : w) wi *= scale;
  return w;
}

}  // namespace alignset

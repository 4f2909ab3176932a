#include "core/optimize/spectrum_weights.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/util/angles.h"

namespace alignset {

std::vector<double> SpectrumLossWeights(const std::vector<Frequency>& k,
                                        const SpectrumWeighting& weighting,
                                        const FrequencyParams& params,
                                        const std::vector<double>& arbitrary_directions) {
  if (weighting.flat() || k.empty()) return {};
  double r_min = std::numeric_limits<double>::infinity();
  for (const Frequency& v : k) r_min = std::min(r_min, std::hypot(v.a, v.b));
  const double p_strip =
      weighting.strip_exponent >= 0.0 ? weighting.strip_exponent : weighting.exponent;
  std::vector<Vec2> normals;
  for (double deg : arbitrary_directions) normals.push_back(UnitVector(deg));
  auto in_arbitrary_strip = [&](const Frequency& v) {
    for (const Vec2& d : normals) {
      if (std::abs(-v.a * d.y + v.b * d.x) <= 0.5 * params.width + 1e-9) return true;
    }
    return false;
  };
  const double knee = std::max(params.radius, r_min);
  std::vector<double> w(k.size());
  double sum = 0.0;
  for (size_t i = 0; i < k.size(); ++i) {
    const double r = std::hypot(k[i].a, k[i].b);
    double wi = r > knee && in_arbitrary_strip(k[i])
                    ? weighting.strip_scale * std::pow(r_min / knee, weighting.exponent) *
                          std::pow(knee / r, p_strip)
                    : std::pow(r_min / r, weighting.exponent);
    if (r <= weighting.low_radius) wi *= weighting.low_boost;
    w[i] = wi;
    sum += wi;
  }
  const double scale = static_cast<double>(k.size()) / sum;
  for (double& wi : w) wi *= scale;
  return w;
}

}  // namespace alignset

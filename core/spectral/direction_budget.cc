#include "core/spectral/direction_budget.h"

#include <algorithm>
#include <cmath>

namespace alignset {

FrequencyParams FrequencyParamsForDirections(uint32_t n, int arbitrary) {
  return FrequencyParamsForDirections(n, arbitrary, 0.5);
}

FrequencyParams FrequencyParamsForDirections(uint32_t n, int arbitrary, double width_exponent) {
  FrequencyParams p = DefaultFrequencyParams(n);
  if (arbitrary <= 2) return p;
  // Share of the two-direction budget per strip: 4 strips -> D strips.
  const double share = 4.0 / (2.0 + arbitrary);
  const double width = std::max(1.0, p.width * std::pow(share, -width_exponent));
  const double length = p.length * p.width * share / width;  // keeps L W = share L0 W0
  p.width = width;
  p.length = std::max(length, p.radius);
  return p;
}

}  // namespace alignset

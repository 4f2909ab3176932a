#pragma once

#include <cstdint>
#include <vector>

#include "core/util/status.h"

namespace alignset {

// An integer frequency v = (a, b) of the torus [0,1)^2.
struct Frequency {
  int32_t a = 0;
  int32_t b = 0;
  friend bool operator==(const Frequency&, const Frequency&) = default;
};

// Shape of the suppressed region K (method.md section 1): a disk |v| <= radius
// and, for every anisotropy direction d, a strip |v.d| <= length,
// |v.d_perp| <= width / 2.
struct FrequencyParams {
  double length = 0.0;
  double width = 0.0;
  double radius = 0.0;
  friend bool operator==(const FrequencyParams&, const FrequencyParams&) = default;
};

// The supplement's parameters for N points.
//
// For the sizes of the supplement's Table 1 (N = 2^12 .. 2^16) they are the
// table's values. Between rows, length, width and radius are interpolated
// geometrically in log N. Outside the table all three scale with sqrt(N) from
// the nearest row, which keeps |K| / N constant because a strip holds about
// length * width frequencies and the half disk pi radius^2 / 2. Two floors
// keep K meaningful for small N: width never drops below 1 (the strip keeps
// its central line; length shrinks instead so that length * width still
// scales with N) and radius never below 1.5.
FrequencyParams SupplementFrequencyParams(uint32_t n);

// The parameters alignset uses (algorithm versions 3 to 5): the supplement's, with
// strips 1.5x as wide and a disk 1.6x the radius. With the weighted loss the
// lowest frequencies are pushed towards zero; a wider disk then darkens the
// isotropic low band (disk and triangle integrands, θ + 45° edges: 0.94 ->
// 0.84 of Owen-Sobol at N = 1024) and a wider strip gives the dark line
// tolerance to a misestimated direction and darker edges at 0°/90°
// (docs/method.md, "The low-frequency floor"). |K| grows to 1.1-1.9 N.
inline constexpr double kDefaultWidthScale = 1.5;
inline constexpr double kDefaultRadiusScale = 1.6;
FrequencyParams DefaultFrequencyParams(uint32_t n);

// The anisotropy directions of a set with arbitrary directions `arbitrary`:
// always 0° and 90°, then the given ones (reduced to [0,180)).
std::vector<double> AnisotropyDirections(const std::vector<double>& arbitrary);

// K: the union of the disk and one strip per direction, DC excluded, one
// representative of each +-v pair (b > 0, or b == 0 and a > 0), sorted by
// (b, a). Deterministic for given inputs.
std::vector<Frequency> BuildFrequencySet(const FrequencyParams& params,
                                         const std::vector<double>& directions_deg);

// Checks parameters before any allocation: positive, finite, and small enough
// that K fits in memory.
Status ValidateFrequencyParams(const FrequencyParams& params);

// The subset of `k` that lies in the strip of one direction (for analysis).
std::vector<Frequency> StripFrequencies(const FrequencyParams& params, double direction_deg);

}  // namespace alignset

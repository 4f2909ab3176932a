#pragma once

#include <cstdint>

#include "core/spectral/frequency_set.h"

namespace alignset {

// The most arbitrary directions a set can have besides the two axes: 1 to 8
// arbitrary ones make 3 to 10 low-energy directions, the range of the
// supplement's Fig. 3.
inline constexpr int kMaxArbitraryDirections = 8;

// How the strips of a set with `arbitrary` arbitrary directions (plus 0° and
// 90°) share the frequency budget.
//
// One and two arbitrary directions keep DefaultFrequencyParams(n) as it is:
// every strip gets the supplement's length L0 and width W0 (the 3-direction
// Table 1 values), so a 4-direction set has 4/3 of a 3-direction set's strip
// frequencies. Beyond that, the budget of the two-direction set is shared:
// the D = 2 + k strips together keep 4 L0 W0 frequencies (a strip holds about
// L W of them, the disk stays as it is), so each strip gets 4 L0 W0 / D.
// Within that, the width grows like sqrt(D / 4) and the length shrinks like
// (4 / D)^1.5: more edge directions mean shorter edges in a polygon of a given
// size, whose spectral lobes are wider across the edge normal (the supplement,
// Fig. 3), so a strip must be wider to cover them; the high frequencies along
// each direction are what gives way (docs/results.md, "Any number of directions", has
// the measurement behind the exponent). The length never drops below the
// disk radius (a strip inside the disk suppresses nothing new) and the width
// never below 1. The result is continuous at k = 2.
FrequencyParams FrequencyParamsForDirections(uint32_t n, int arbitrary);

// The same rule with the width exponent as a parameter (0: the width stays
// W0 and only the length shrinks), for the measurement that chose 0.5.
FrequencyParams FrequencyParamsForDirections(uint32_t n, int arbitrary, double width_exponent);

}  // namespace alignset

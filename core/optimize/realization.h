#pragma once

#include <cstdint>

#include "core/util/hash.h"

namespace alignset {

// Realizations: independent optimized sets for the same key (N, directions,
// profile), each from its own start. A renderer gives neighbouring pixels or
// successive frames different realizations, so they do not all share one
// pattern up to their Cranley-Patterson shifts.
//
// Realization 0 is the set the key always had: its seed is the base seed
// itself, so every set cached before realizations existed is realization 0
// and stays valid. Realization r > 0 starts from a hash of (base seed, r): a
// plain `base + r` would make realization 1 of seed 1 the same set as
// realization 0 of seed 2.
inline constexpr uint32_t kMaxRealization = 63;

inline uint64_t RealizationSeed(uint64_t base_seed, uint32_t realization) {
  return realization == 0 ? base_seed : HashCombine(base_seed, realization);
}

}  // namespace alignset

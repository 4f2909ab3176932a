#pragma once

#include <cstdint>
#include <map>
#include <set>
#include <utility>
#include <vector>

#include "render/direction.h"
#include "core/util/point_set.h"

namespace alignset::render {

// The direction a server serves for a requested θ: the nearest whole degree,
// reduced mod 180 (ties away from zero), as core/align's Canonicalize does.
int ServedDegree(double theta_deg);

// What a pixel without a dominant direction gets, and whether pixels with
// two get a two-direction (4-direction) set.
struct AlignedPolicy {
  enum class None { kOwenSobol, kAxisSet };
  None none = None::kOwenSobol;
  bool two_directions = true;
};

// The set a pixel gets, in served whole degrees.
//  - kFallback: no dominant direction and policy kOwenSobol.
//  - kOne(a): one direction a; also a pixel whose second direction is an
//    axis (0 or 90 after rounding): every set already suppresses the axes,
//    so a 4-direction set would spend its strips twice. A pixel without a
//    dominant direction under kAxisSet gets kOne(0), the axis set.
//  - kTwo(a, b), a < b: two distinct non-axis directions.
struct SetChoice {
  enum class Kind { kFallback, kOne, kTwo };
  Kind kind = Kind::kFallback;
  int a = 0;
  int b = 0;
};
SetChoice ChooseSet(const PixelDirection& d, const AlignedPolicy& policy);

// The pairs a direction map needs under a policy.
std::set<std::pair<int, int>> NeededPairs(const std::vector<PixelDirection>& directions,
                                          const AlignedPolicy& policy);

// The aligned sets of one N a render reads: the 180 one-direction sets by
// served degree, and the two-direction sets it needs by (a, b). Filled
// before rendering (render/set_fetch.h fetches them from a server);
// read-only while the render's threads run.
struct AlignedSetTable {
  uint32_t n = 0;
  std::vector<PointSet> one;                       // one[k], k in [0, 180); empty: not fetched
  std::map<std::pair<int, int>, PointSet> two;     // by (a, b), a < b
  const PointSet* One(int served_deg) const;
  const PointSet* Two(int a, int b) const;
};

}  // namespace alignset::render

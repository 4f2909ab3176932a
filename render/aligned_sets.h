#pragma once

#include <cstdint>
#include <map>
#include <set>
#include <utility>
#include <vector>

#include <alignset/pixel_sampler.h>

#include "render/direction.h"
#include "core/util/point_set.h"

namespace alignset::render {

// The set choice is the client library's per-pixel recipe
// (<alignset/pixel_sampler.h>: AlignedPolicy, SetChoice, ChooseSet); a
// render's direction map is turned into its PixelDirections here.
inline PixelDirections RecipeDirections(const PixelDirection& d) {
  return {static_cast<int>(d.kind), d.theta1, d.theta2};
}

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
  // Tent-folded lattices (render/lattice_sets.h): the sets are the lattices
  // unfolded; a pixel folds each point by 1 - |2u - 1| after its shift.
  bool folded = false;
  const PointSet* One(int served_deg) const;
  const PointSet* Two(int a, int b) const;
};

}  // namespace alignset::render

#pragma once

#include <cstdint>
#include <map>
#include <set>
#include <utility>
#include <vector>

#include <alignset/set_choice.h>
#include <alignset/set_table.h>

#include "render/direction.h"
#include "core/util/point_set.h"

namespace alignset::render {

// The set choice is the sampler library's per-pixel recipe
// (<alignset/set_choice.h>: AlignedPolicy, SetChoice, ChooseSet); a
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
  // A lattice table's generators beside its points (0: not a lattice), so
  // that a pixel's points come from the sampler library (SetPixelPoints).
  std::vector<uint32_t> one_generator;             // by served degree, like `one`
  std::map<std::pair<int, int>, uint32_t> two_generator;
  const PointSet* One(int served_deg) const;
  const PointSet* Two(int a, int b) const;
  // The served set of a choice as the sampler library reads it; points null
  // when the table was not filled with it.
  TableSet Served(const SetChoice& c) const;
};

}  // namespace alignset::render

#pragma once

#include <cstdint>
#include <memory>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include <alignset/set_choice.h>
#include <alignset/set_table.h>

#include "render/direction.h"
#include "core/util/status.h"

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

// The aligned sets a render reads: the sampler library's table
// (<alignset/set_table.h>), holding the keys of one N and one construction
// that the render's pixels choose (render/set_fetch.h fetches them from a
// server, render/lattice_sets.h searches lattices here), aligned per pixel
// as any renderer's would be. Read-only while the render's threads run.
struct RenderSets {
  std::shared_ptr<const SetTable> table;  // null: no pixel needs a set
  uint32_t n = 0;
  std::string construction;  // the sections': "optimized", "lattice" or "tent-lattice"
};

// The canonical keys (core/align/canonical.h's CanonicalKeyIndex) of served
// pairs (a, b), ascending: the keys a table must hold for them.
std::vector<uint32_t> PairKeys(const std::set<std::pair<int, int>>& pairs);

// A render's sets from the sections that hold its keys, each listing them
// (a section listing every key of its space becomes whole; one listing none
// is left out, and a render whose pixels need no key has no table).
// INVALID_ARGUMENT as SetTable::FromSections.
StatusOr<RenderSets> MakeRenderSets(uint32_t n, const std::string& construction, std::vector<TableSection> sections);

}  // namespace alignset::render

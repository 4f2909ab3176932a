#include "render/aligned_sets.h"

namespace alignset::render {

std::set<std::pair<int, int>> NeededPairs(const std::vector<PixelDirection>& directions,
                                          const AlignedPolicy& policy) {
  std::set<std::pair<int, int>> out;
  for (const PixelDirection& d : directions) {
    const SetChoice c = ChooseSet(RecipeDirections(d), policy);
    if (c.kind == SetChoice::Kind::kTwo) out.insert({c.a, c.b});
  }
  return out;
}

const PointSet* AlignedSetTable::One(int served_deg) const {
  if (served_deg < 0 || served_deg >= static_cast<int>(one.size())) return nullptr;
  return one[served_deg].empty() ? nullptr : &one[served_deg];
}

const PointSet* AlignedSetTable::Two(int a, int b) const {
  auto it = two.find({std::min(a, b), std::max(a, b)});
  return it == two.end() ? nullptr : &it->second;
}

}  // namespace alignset::render

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

TableSet AlignedSetTable::Served(const SetChoice& c) const {
  TableSet out;
  const PointSet* points = nullptr;
  uint32_t g = 0;
  if (c.kind == SetChoice::Kind::kOne) {
    points = One(c.a);
    if (points && c.a < static_cast<int>(one_generator.size())) g = one_generator[c.a];
  } else if (c.kind == SetChoice::Kind::kTwo) {
    points = Two(c.a, c.b);
    if (auto it = two_generator.find({std::min(c.a, c.b), std::max(c.a, c.b)}); points && it != two_generator.end()) {
      g = it->second;
    }
  }
  if (!points) return out;
  out.n = static_cast<uint32_t>(points->size());
  out.lattice_generator = g;
  out.folded = g != 0 && folded;
  out.points = points;
  return out;
}

}  // namespace alignset::render

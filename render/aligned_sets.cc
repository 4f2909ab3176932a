#include "render/aligned_sets.h"

#include <algorithm>

#include "core/align/canonical.h"

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

std::vector<uint32_t> PairKeys(const std::set<std::pair<int, int>>& pairs) {
  std::vector<uint32_t> keys;
  for (const auto& [a, b] : pairs) {
    const auto c = Canonicalize({static_cast<double>(a), static_cast<double>(b)});
    keys.push_back(static_cast<uint32_t>(*CanonicalKeyIndex(c->key)));
  }
  std::sort(keys.begin(), keys.end());
  keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
  return keys;
}

StatusOr<RenderSets> MakeRenderSets(uint32_t n, const std::string& construction, std::vector<TableSection> sections) {
  RenderSets out;
  out.n = n;
  out.construction = construction;
  std::erase_if(sections, [](const TableSection& s) { return s.keys.empty(); });
  for (TableSection& s : sections) {
    if (s.keys.size() == TableSpaceKeys(s.space)) s.keys.clear();  // every key: a whole section
  }
  if (sections.empty()) return out;
  auto table = SetTable::FromSections(std::move(sections));
  if (!table.ok()) return table.status();
  out.table = std::move(*table);
  return out;
}

}  // namespace alignset::render

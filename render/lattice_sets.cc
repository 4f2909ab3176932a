#include "render/lattice_sets.h"

#include <algorithm>
#include <chrono>
#include <map>
#include <set>
#include <string>
#include <utility>

#include "core/align/canonical.h"
#include "core/optimize/aligned_lattice.h"

namespace alignset::render {

Status CheckLatticeSizeSpan(uint32_t n, uint32_t size_span) {
  if (size_span > 0 && (n < 16 || size_span > n - 16)) {
    return Status::InvalidArgument("a lattice size span of " + std::to_string(size_span) + " leaves N = " +
                                   std::to_string(n) + " below 16 points");
  }
  return Status::Ok();
}

StatusOr<RenderSets> AlignedLatticeTable(
    uint32_t n, const std::vector<const std::vector<PixelDirection>*>& direction_maps,
    const AlignedPolicy& policy, double window_deg, int threads, LatticeTableStats* stats,
    const std::function<void(double done, double total)>& progress, bool folded, uint32_t size_span) {
  const auto t0 = std::chrono::steady_clock::now();
  // Checked up front, so that a bad N or window is refused even when no
  // pixel needs a lattice.
  if (n < 16 || n > (1u << 20)) {
    return Status::InvalidArgument("aligned lattices need N in [16, 1048576], got " + std::to_string(n));
  }
  if (!(window_deg >= 0.0 && window_deg <= 10.0)) {
    return Status::InvalidArgument("the lattice window must be in [0, 10] degrees");
  }
  if (Status s = CheckLatticeSizeSpan(n, size_span); !s.ok()) return s;
  // Every served degree and pair is the image of a canonical key under a
  // symmetry of the square (core/align/canonical.h), and the lattice chosen
  // for the key maps onto one the search would score as well for the
  // image (MapLatticeGenerator): so one search per key, at most 46
  // one-direction keys for the 180 degrees.
  std::set<int> ones;
  std::set<std::pair<int, int>> twos;
  for (const auto* map : direction_maps) {
    for (const PixelDirection& d : *map) {
      const SetChoice c = ChooseSet(RecipeDirections(d), policy);
      if (c.kind == SetChoice::Kind::kOne) ones.insert(c.a);
      if (c.kind == SetChoice::Kind::kTwo) twos.insert({std::min(c.a, c.b), std::max(c.a, c.b)});
    }
  }
  struct Served {
    Canonicalization how;
    int one = -1;                    // the served degree, or
    std::pair<int, int> two{-1, -1};  // the served pair
  };
  std::vector<Served> served;
  struct Chosen {
    uint32_t n = 0, generator = 0;  // 0: not chosen yet
    double score = 0.0;
  };
  std::map<std::pair<int, int>, Chosen> by_key;  // (phi1, phi2) -> its lattice
  auto add = [&](std::vector<double> dirs, int one, std::pair<int, int> two) -> Status {
    auto how = Canonicalize(dirs);
    if (!how.ok()) return how.status();
    by_key[{how->key.phi1, how->key.phi2}] = Chosen{};
    served.push_back({std::move(*how), one, two});
    return Status::Ok();
  };
  for (int a : ones) {
    if (Status s = add({static_cast<double>(a)}, a, {-1, -1}); !s.ok()) return s;
  }
  for (const auto& [a, b] : twos) {
    if (Status s = add({static_cast<double>(a), static_cast<double>(b)}, -1, {a, b}); !s.ok()) return s;
  }
  AlignedLatticeOptions o;
  o.folded = folded;
  o.window_deg = window_deg;
  o.threads = threads;
  // All keys in one call: the first stage's work per degree is shared by
  // every pair the degree is in.
  std::vector<std::vector<double>> keys;
  for (const auto& entry : by_key) {
    const std::pair<int, int>& key = entry.first;
    keys.push_back({static_cast<double>(key.first)});
    if (key.second != key.first) keys.back().push_back(static_cast<double>(key.second));
  }
  // Largest size first, so that a tie keeps the larger.
  for (uint32_t size = n; size + size_span >= n; --size) {
    const double pass = n - size, passes = size_span + 1.0;
    auto choices = ChooseAlignedLatticeGenerators(size, keys, o, [&](double done, double total) {
      if (progress && total > 0.0) progress((pass + done / total) / passes, 1.0);
    });
    if (!choices.ok()) return choices.status();
    size_t k = 0;
    for (auto& entry : by_key) {
      const AlignedLatticeChoice& c = (*choices)[k++];
      if (entry.second.n == 0 || c.score < entry.second.score) entry.second = {size, c.generator, c.score};
    }
  }
  // The table holds each key's own lattice; a pixel's lookup carries it
  // onto the served degree or pair (MapLatticeGenerator). One realization
  // for every pixel: the per-pixel Cranley-Patterson shift is what
  // decorrelates pixels (and keeps each unbiased), and it goes before a
  // tent-lattice's fold (the tent is even and mirrors to a half shift, so
  // the mirrored key's generator N - g folds to the same sets as g).
  TableSection whole, two;
  for (TableSection* t : {&whole, &two}) {
    t->n = n;
    t->construction = folded ? "tent-lattice" : "lattice";
  }
  whole.space = TableSpace::kOneDirection;
  two.space = TableSpace::kTwoDirections;
  std::map<uint32_t, const Chosen*> by_index[2];  // the keys held, ascending, per section
  for (const Served& s : served) {
    by_index[s.one >= 0 ? 0 : 1][static_cast<uint32_t>(*CanonicalKeyIndex(s.how.key))] =
        &by_key.at({s.how.key.phi1, s.how.key.phi2});
  }
  for (int i = 0; i < 2; ++i) {
    TableSection& t = i == 0 ? whole : two;
    for (const auto& [index, chosen] : by_index[i]) {
      t.keys.push_back(index);
      t.generators.push_back(chosen->generator);
      t.sizes.push_back(chosen->n);
    }
    if (std::all_of(t.sizes.begin(), t.sizes.end(), [n](uint32_t size) { return size == n; })) t.sizes.clear();
  }
  const std::string construction = whole.construction;
  auto table = MakeRenderSets(n, construction, {std::move(whole), std::move(two)});
  if (!table.ok()) return table.status();
  if (stats) {
    stats->one = ones.size();
    stats->two = twos.size();
    stats->searched = by_key.size() * (size_span + 1);
    stats->smaller = 0;
    double points = 0.0;
    for (const auto& entry : by_key) {
      stats->smaller += entry.second.n < n;
      points += entry.second.n;
    }
    stats->mean_points = by_key.empty() ? n : points / static_cast<double>(by_key.size());
    stats->seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  }
  return table;
}

}  // namespace alignset::render

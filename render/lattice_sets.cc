#include "render/lattice_sets.h"

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

StatusOr<AlignedSetTable> AlignedLatticeTable(
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
  AlignedSetTable table;
  table.n = n;
  table.folded = folded;
  table.one.resize(180);
  table.one_generator.assign(180, 0);
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
  for (const Served& s : served) {
    const Chosen& key = by_key.at({s.how.key.phi1, s.how.key.phi2});
    const uint32_t g =
        MapLatticeGenerator(key.n, key.generator, s.how.ops.swap, s.how.ops.invert, s.how.ops.invert_y);
    // One realization for every pixel: the per-pixel Cranley-Patterson
    // shift is what decorrelates pixels (and keeps each unbiased). Folded,
    // the lattice is stored unfolded and the sampler folds after the shift
    // (the tent is even and mirrors to a half shift, so the generator of
    // the mirrored key, N - g, folds to the same sets as g).
    PointSet points = Rank1LatticePoints(key.n, g, 0);
    if (s.one >= 0) {
      table.one[s.one] = std::move(points);
      table.one_generator[s.one] = g;
    } else {
      table.two[s.two] = std::move(points);
      table.two_generator[s.two] = g;
    }
  }
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

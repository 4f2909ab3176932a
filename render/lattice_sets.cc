#include "render/lattice_sets.h"

#include <chrono>
#include <set>
#include <string>
#include <utility>

#include "core/optimize/aligned_lattice.h"

namespace alignset::render {

StatusOr<AlignedSetTable> AlignedLatticeTable(
    uint32_t n, const std::vector<const std::vector<PixelDirection>*>& direction_maps,
    const AlignedPolicy& policy, double window_deg, int threads, LatticeTableStats* stats,
    const std::function<void(double done, double total)>& progress) {
  const auto t0 = std::chrono::steady_clock::now();
  // Checked up front, so that a bad N or window is refused even when no
  // pixel needs a lattice.
  if (n < 16 || n > (1u << 20)) {
    return Status::InvalidArgument("aligned lattices need N in [16, 1048576], got " + std::to_string(n));
  }
  if (!(window_deg >= 0.0 && window_deg <= 10.0)) {
    return Status::InvalidArgument("the lattice window must be in [0, 10] degrees");
  }
  std::set<int> ones;
  std::set<std::pair<int, int>> twos;
  for (const auto* map : direction_maps) {
    for (const PixelDirection& d : *map) {
      const SetChoice c = ChooseSet(RecipeDirections(d), policy);
      if (c.kind == SetChoice::Kind::kOne) ones.insert(c.a);
      if (c.kind == SetChoice::Kind::kTwo) twos.insert({std::min(c.a, c.b), std::max(c.a, c.b)});
    }
  }
  AlignedLatticeOptions o;
  o.window_deg = window_deg;
  o.threads = threads;
  AlignedSetTable table;
  table.n = n;
  table.one.resize(180);
  const double total = static_cast<double>(ones.size() + twos.size());
  double done = 0.0;
  auto make = [&](const std::vector<double>& dirs) -> StatusOr<PointSet> {
    auto choice = ChooseAlignedLatticeGenerator(n, dirs, o);
    if (!choice.ok()) return choice.status();
    if (progress) progress(++done, total);
    // One realization for every pixel: the per-pixel Cranley-Patterson
    // shift is what decorrelates pixels (and keeps each unbiased).
    return Rank1LatticePoints(n, choice->generator, 0);
  };
  for (int a : ones) {
    auto set = make({static_cast<double>(a)});
    if (!set.ok()) return set.status();
    table.one[a] = std::move(*set);
  }
  for (const auto& [a, b] : twos) {
    auto set = make({static_cast<double>(a), static_cast<double>(b)});
    if (!set.ok()) return set.status();
    table.two[{a, b}] = std::move(*set);
  }
  if (stats) {
    stats->one = ones.size();
    stats->two = twos.size();
    stats->seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  }
  return table;
}

}  // namespace alignset::render

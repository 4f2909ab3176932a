#include "render/set_fetch.h"

#include <algorithm>
#include <vector>

#include "core/optimize/aligned_lattice.h"
#include "core/optimize/construction.h"

namespace alignset::render {
namespace {

// The request for a choice's set of N points made by `construction` ("" the
// server's default); a fallback choice asks for none.
SetRequest RequestFor(const SetChoice& c, uint32_t n, const std::string& construction) {
  SetRequest r;
  r.n = n;
  r.construction = construction;
  r.directions_deg = {static_cast<double>(c.a)};
  if (c.kind == SetChoice::Kind::kTwo) r.directions_deg.push_back(static_cast<double>(c.b));
  return r;
}

}  // namespace

StatusOr<AlignedSetTable> FetchAlignedSets(ServiceClient& client, uint32_t n,
                                           const std::set<std::pair<int, int>>& pairs,
                                           const FetchProgressFn& progress,
                                           const std::string& construction) {
  const Construction* made = FindConstruction(construction);
  if (made == nullptr || !(made->optimized() || made->lattice())) {
    return Status::InvalidArgument("a render reads optimized sets or lattices, not '" + construction + "'");
  }
  const bool lattice = made->lattice();
  const std::string what = lattice ? construction : "optimize";
  auto report = [&](const std::string& stage, double done, double total, const std::string& d) {
    if (progress) progress(stage, done, total, d);
  };
  auto precompute = [&](const PrecomputeSpec& spec, const std::string& stage) -> Status {
    auto r = client.Precompute(spec, [&](const PrecomputeUpdate& u) {
      report(stage, static_cast<double>(u.done + u.cached_already + u.failed),
             static_cast<double>(u.total),
             u.last_key.empty() ? std::string() : "last " + u.last_key);
    });
    if (!r.ok()) return r.status();
    if (r->failed > 0) {
      return Status::Internal(stage + ": " + std::to_string(r->failed) +
                              " keys failed on the server: " + r->last_error);
    }
    return Status::Ok();
  };
  PrecomputeSpec one;
  one.n = {n};
  one.space = 1;
  one.construction = construction;
  if (Status s = precompute(one, what + " 1-dir space N=" + std::to_string(n)); !s.ok()) return s;
  if (!pairs.empty()) {
    PrecomputeSpec two;
    two.n = {n};
    two.space = 0;
    two.construction = construction;
    for (const auto& [a, b] : pairs) two.keys.push_back({a, b});
    if (Status s = precompute(two, what + " 2-dir keys N=" + std::to_string(n)); !s.ok()) return s;
  }

  AlignedSetTable table;
  table.n = n;
  table.folded = made->folded();
  table.one.resize(180);
  table.one_generator.assign(180, 0);
  std::vector<SetRequest> items;
  for (int deg = 0; deg < 180; ++deg) items.push_back(RequestFor({SetChoice::Kind::kOne, deg, 0}, n, construction));
  for (const auto& [a, b] : pairs) items.push_back(RequestFor({SetChoice::Kind::kTwo, a, b}, n, construction));
  const std::string stage = "fetch sets N=" + std::to_string(n);
  for (size_t begin = 0; begin < items.size(); begin += kMaxBatchItems) {
    const size_t end = std::min(items.size(), begin + kMaxBatchItems);
    auto batch = client.GetAlignedSets({items.begin() + begin, items.begin() + end});
    if (!batch.ok()) return batch.status();
    if (batch->size() != end - begin) return Status::Internal("batch answered " + std::to_string(batch->size()) + " items of " + std::to_string(end - begin));
    for (size_t i = begin; i < end; ++i) {
      BatchItem& item = (*batch)[i - begin];
      if (!item.status.ok()) return item.status;
      if (lattice) {
        // The served generator, aligned already: the same unfolded lattice
        // the local table would hold.
        const uint32_t g = item.set.info.lattice_generator;
        if (g == 0) {
          return Status::FailedPrecondition("the server does not report lattice generators (update it)");
        }
        item.set.points = Rank1LatticePoints(n, g, 0);
      }
      if (i < 180) {
        const int deg = static_cast<int>(i);
        if (item.set.info.served_deg.size() != 1 || item.set.info.served_deg[0] != deg) {
          return Status::Internal("server served a different direction for " + std::to_string(deg) + " deg");
        }
        table.one[deg] = std::move(item.set.points);
        if (lattice) table.one_generator[deg] = item.set.info.lattice_generator;
      } else {
        const int a = static_cast<int>(items[i].directions_deg[0]), b = static_cast<int>(items[i].directions_deg[1]);
        table.two[{a, b}] = std::move(item.set.points);
        if (lattice) table.two_generator[{a, b}] = item.set.info.lattice_generator;
      }
    }
    report(stage, static_cast<double>(end), static_cast<double>(items.size()), "");
  }
  return table;
}

}  // namespace alignset::render

#include "render/set_fetch.h"

#include <algorithm>
#include <vector>

#include "core/align/canonical.h"
#include "core/optimize/construction.h"

namespace alignset::render {
namespace {

// The request for a canonical key's set of N points made by `construction`
// ("" the server's default): the key's own directions, which the server
// serves unaligned (the identity carries a key onto itself).
SetRequest KeyRequest(const CanonicalDirections& key, int count, uint32_t n, const std::string& construction) {
  SetRequest r;
  r.n = n;
  r.construction = construction;
  r.directions_deg = {Phi1Degrees(key)};
  if (count == 2) r.directions_deg.push_back(Phi2Degrees(key));
  return r;
}

}  // namespace

StatusOr<RenderSets> FetchAlignedSets(ServiceClient& client, uint32_t n,
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

  // Every one-direction key and the pairs' keys, as the server stores them;
  // the table aligns them per pixel.
  TableSection whole, two;
  for (TableSection* s : {&whole, &two}) {
    s->n = n;
    s->construction = std::string(made->name);
  }
  whole.space = TableSpace::kOneDirection;
  two.space = TableSpace::kTwoDirections;
  for (uint32_t k = 0; k < TableSpaceKeys(TableSpace::kOneDirection); ++k) whole.keys.push_back(k);
  two.keys = PairKeys(pairs);
  std::vector<std::pair<TableSection*, uint32_t>> wanted;  // (section, key)
  for (TableSection* s : {&whole, &two}) {
    for (uint32_t k : s->keys) wanted.push_back({s, k});
  }
  const std::string stage = "fetch sets N=" + std::to_string(n);
  for (size_t begin = 0; begin < wanted.size(); begin += kMaxBatchItems) {
    const size_t end = std::min(wanted.size(), begin + kMaxBatchItems);
    std::vector<SetRequest> items;
    for (size_t i = begin; i < end; ++i) {
      const int count = wanted[i].first == &two ? 2 : 1;
      items.push_back(KeyRequest(CanonicalKeyAt(count, wanted[i].second), count, n, construction));
      // What the server serves for a key's own directions is the stored set
      // only if the identity is what carries the key onto them.
      const auto how = Canonicalize(items.back().directions_deg);
      if (!how.ok() || how->ops != AlignOps{}) {
        return Status::Internal("canonical key " + std::to_string(wanted[i].second) + " is not served as stored");
      }
    }
    auto batch = client.GetAlignedSets(items);
    if (!batch.ok()) return batch.status();
    if (batch->size() != items.size()) {
      return Status::Internal("batch answered " + std::to_string(batch->size()) + " items of " +
                              std::to_string(items.size()));
    }
    for (size_t i = begin; i < end; ++i) {
      BatchItem& item = (*batch)[i - begin];
      if (!item.status.ok()) return item.status;
      std::vector<double> served(item.set.info.served_deg.begin(), item.set.info.served_deg.end()),
          asked = items[i - begin].directions_deg;
      std::sort(served.begin(), served.end());
      std::sort(asked.begin(), asked.end());
      if (served != asked) {
        return Status::Internal("server served other directions for a canonical key");
      }
      TableSection& s = *wanted[i].first;
      if (lattice) {
        const uint32_t g = item.set.info.lattice_generator;
        if (g == 0) {
          return Status::FailedPrecondition("the server does not report lattice generators (update it)");
        }
        s.generators.push_back(g);
      } else {
        s.sets.push_back(std::move(item.set.points));
      }
    }
    report(stage, static_cast<double>(end), static_cast<double>(wanted.size()), "");
  }
  const std::string name = whole.construction;  // read before the sections move
  return MakeRenderSets(n, name, {std::move(whole), std::move(two)});
}

}  // namespace alignset::render

#include "bench/render/set_fetch.h"

namespace alignset::render {

StatusOr<AlignedSetTable> FetchAlignedSets(cli::ServiceClient& client, uint32_t n,
                                           const std::set<std::pair<int, int>>& pairs,
                                           const FetchProgressFn& progress) {
  auto report = [&](const std::string& stage, double done, double total, const std::string& d) {
    if (progress) progress(stage, done, total, d);
  };
  auto precompute = [&](const cli::PrecomputeSpec& spec, const std::string& stage) -> Status {
    auto r = client.Precompute(spec, [&](const cli::PrecomputeUpdate& u) {
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
  cli::PrecomputeSpec one;
  one.n = {n};
  one.space = 1;
  if (Status s = precompute(one, "optimize 1-dir space N=" + std::to_string(n)); !s.ok()) return s;
  if (!pairs.empty()) {
    cli::PrecomputeSpec two;
    two.n = {n};
    two.space = 0;
    for (const auto& [a, b] : pairs) two.keys.push_back({a, b});
    if (Status s = precompute(two, "optimize 2-dir keys N=" + std::to_string(n)); !s.ok()) return s;
  }

  AlignedSetTable table;
  table.n = n;
  table.one.resize(180);
  const double total = 180.0 + static_cast<double>(pairs.size());
  double done = 0.0;
  for (int deg = 0; deg < 180; ++deg) {
    auto set = client.GetAlignedSet(n, {static_cast<double>(deg)});
    if (!set.ok()) return set.status();
    if (set->info.served_deg.size() != 1 || set->info.served_deg[0] != deg) {
      return Status::Internal("server served a different direction for " + std::to_string(deg) + "°");
    }
    table.one[deg] = std::move(set->points);
    report("fetch sets N=" + std::to_string(n), ++done, total, "");
  }
  for (const auto& [a, b] : pairs) {
    auto set = client.GetAlignedSet(n, {static_cast<double>(a), static_cast<double>(b)});
    if (!set.ok()) return set.status();
    table.two[{a, b}] = std::move(set->points);
    report("fetch sets N=" + std::to_string(n), ++done, total, "");
  }
  return table;
}

}  // namespace alignset::render

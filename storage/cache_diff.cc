#include "storage/cache_diff.h"

#include <algorithm>
#include <cstring>
#include <tuple>

namespace alignset::storage {
namespace {

// Every key field, the profile included (List orders by the others only).
auto Order(const SetKey& k) {
  return std::tie(k.n, k.dirs.count, k.dirs.phi1, k.dirs.phi2, k.dirs.phi1_quarter, k.realization,
                  k.profile);
}

bool Before(const SetKey& a, const SetKey& b) { return Order(a) < Order(b); }

// Bit for bit: -0.0 against 0.0 is a difference, as a server would serve it.
int64_t PointsDiffering(const PointSet& a, const PointSet& b) {
  if (a.size() != b.size()) return static_cast<int64_t>(std::max(a.size(), b.size()));
  int64_t count = 0;
  for (size_t i = 0; i < a.size(); ++i) {
    if (std::memcmp(&a[i], &b[i], sizeof(Point2)) != 0) ++count;
  }
  return count;
}

}  // namespace

StatusOr<CacheDiff> DiffCaches(SetCache& first, SetCache& second, std::optional<uint32_t> n,
                               std::optional<std::string> profile) {
  auto keys_a = first.List(n, profile);
  if (!keys_a.ok()) return keys_a.status();
  auto keys_b = second.List(n, profile);
  if (!keys_b.ok()) return keys_b.status();
  std::sort(keys_a->begin(), keys_a->end(), Before);
  std::sort(keys_b->begin(), keys_b->end(), Before);

  CacheDiff diff;
  auto a = keys_a->begin(), b = keys_b->begin();
  while (a != keys_a->end() || b != keys_b->end()) {
    if (b == keys_b->end() || (a != keys_a->end() && Before(*a, *b))) {
      diff.only_first.push_back(*a++);
      continue;
    }
    if (a == keys_a->end() || Before(*b, *a)) {
      diff.only_second.push_back(*b++);
      continue;
    }
    const SetKey& key = *a;
    auto ra = first.Get(key);
    auto rb = second.Get(key);
    for (const auto* r : {&ra, &rb}) {
      if (!r->ok() && r->status().code() != Status::Code::kDataLoss) return r->status();
    }
    if (!ra.ok() || !rb.ok()) {
      diff.damaged.push_back({key, !ra.ok(), !rb.ok()});
    } else if (const int64_t d = PointsDiffering(ra->points, rb->points); d > 0) {
      diff.differing.push_back({key, d});
    } else {
      ++diff.same;
    }
    ++a;
    ++b;
  }
  return diff;
}

}  // namespace alignset::storage

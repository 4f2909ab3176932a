// The parts of set_cache.h that do not depend on SQLite.
#include "storage/set_cache.h"

#include <string>

#include "core/optimize/point_count.h"

namespace alignset::storage {

Status ValidateKey(const SetKey& key) {
  if (Status s = ValidatePointCount(key.n); !s.ok()) return s;
  const CanonicalDirections& d = key.dirs;
  if (d.count == 1) {
    if (d.phi1 < 0 || d.phi1 > 45 || d.phi2 != d.phi1) {
      return Status::InvalidArgument("a one-direction key needs phi1 in [0, 45] and phi2 == phi1");
    }
    if (d.phi1_quarter < 0 || d.phi1_quarter > 3 || (d.phi1 == 45 && d.phi1_quarter != 0)) {
      return Status::InvalidArgument("a one-direction key's angle is a multiple of 1/4 degree in [0, 45]");
    }
  } else if (d.count == 2) {
    if (d.phi1 < 0 || d.phi1 > d.phi2 || d.phi2 >= 180) {
      return Status::InvalidArgument("a two-direction key needs 0 <= phi1 <= phi2 < 180");
    }
    if (d.phi1_quarter != 0) {
      return Status::InvalidArgument("a two-direction key has whole degrees");
    }
  } else {
    return Status::InvalidArgument("a key has 1 or 2 arbitrary directions, not " +
                                   std::to_string(d.count));
  }
  if (key.realization > kMaxRealization) {
    return Status::InvalidArgument("realization " + std::to_string(key.realization) +
                                   " is above the maximum of " + std::to_string(kMaxRealization));
  }
  if (key.profile.empty() || key.profile.size() > 64) {
    return Status::InvalidArgument("a profile id has 1 to 64 characters");
  }
  for (char c : key.profile) {
    const bool ok = (c >= '0' && c <= '9') || (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') ||
                    c == '.' || c == '_' || c == '-';
    if (!ok) return Status::InvalidArgument("a profile id may hold only [A-Za-z0-9._-]");
  }
  return Status::Ok();
}

std::string KeyToString(const SetKey& key) {
  std::string s = "n=";
  s += std::to_string(key.n);
  s += " dirs=";
  s += std::to_string(key.dirs.count);
  s += ':';
  s += FormatGridAngle(Phi1Degrees(key.dirs));
  if (key.dirs.count == 2) {
    s += ',';
    s += std::to_string(key.dirs.phi2);
  }
  if (key.realization > 0) {
    s += " r=";
    s += std::to_string(key.realization);
  }
  s += " profile=";
  s += key.profile;
  return s;
}

StatusOr<std::vector<SetSummary>> SetCache::ListSummaries(std::optional<uint32_t> n,
                                                          std::optional<std::string> profile) {
  auto keys = List(n, profile);
  if (!keys.ok()) return keys.status();
  std::vector<SetSummary> out;
  for (const SetKey& key : *keys) {
    auto rec = Get(key);
    if (!rec.ok()) return rec.status();
    SetSummary s;
    s.key = key;
    s.loss = rec->loss;
    s.iterations = rec->iterations;
    s.optimize_seconds = rec->optimize_seconds;
    s.engine = rec->engine;
    s.created_unix = rec->created_unix;
    s.algorithm_version = rec->algorithm_version;
    s.bytes = static_cast<int64_t>(rec->points.size() * 16);
    out.push_back(std::move(s));
  }
  return out;
}

Status SetCache::Delete(const SetKey&) { return Status::Internal("this cache cannot delete sets"); }
StatusOr<FileSpace> SetCache::Space() { return Status::Internal("this cache has no file"); }
Status SetCache::EnableIncrementalVacuum() { return Status::Internal("this cache has no file"); }
StatusOr<int64_t> SetCache::IncrementalVacuum(int64_t) {
  return Status::Internal("this cache has no file");
}

}  // namespace alignset::storage

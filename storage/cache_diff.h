#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/util/status.h"
#include "storage/set_cache.h"

namespace alignset::storage {

// Two cache files compared set by set. A set is a function of its key
// (core/align/key_lineage.h): two servers of one deployment, two shards of one
// precompute, or a fill before and after a change that must not move the
// sets, hold the same points under every key they share, bit for bit. The
// metadata (timings, creation time, engine name) is not compared: it
// differs between two fills of the same set.
struct CacheDiff {
  struct Differing {
    SetKey key;
    int64_t points = 0;  // how many of its points differ
  };
  // A shared key whose row fails its checksum (DataLoss on read).
  struct Damaged {
    SetKey key;
    bool in_first = false;
    bool in_second = false;
  };
  int64_t same = 0;  // shared keys whose points are bit-identical
  std::vector<Differing> differing;
  std::vector<Damaged> damaged;
  std::vector<SetKey> only_first;   // keys the second file lacks
  std::vector<SetKey> only_second;  // keys the first file lacks

  // Nothing differs and nothing is damaged among the shared keys.
  bool SharedAgree() const { return differing.empty() && damaged.empty(); }
};

// Compares every key of `first` and `second` (optionally only those of one
// N and / or one profile). Errors other than a damaged row (a file that is
// not a cache, an I/O error) are returned.
StatusOr<CacheDiff> DiffCaches(SetCache& first, SetCache& second,
                               std::optional<uint32_t> n = std::nullopt,
                               std::optional<std::string> profile = std::nullopt);

}  // namespace alignset::storage

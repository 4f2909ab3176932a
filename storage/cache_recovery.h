#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "core/util/status.h"
#include "storage/set_cache.h"

namespace alignset::storage {

// Page-level damage in a cache file (a torn or bit-flipped B-tree page, a
// bad root pointer): what SQLite's own check says, which sets can still be
// read, and which cannot. Used by `alignset cache verify` / `recover`, by
// SetCache::Verify, and by the server's start-up check.

// PRAGMA quick_check on a read-only connection: the problems it lists (at
// most `max_problems`, plus the error that stopped it, if one did), empty
// when it answers "ok". DataLoss when the file cannot even be read as a
// database.
StatusOr<std::vector<std::string>> QuickCheck(const std::string& path, int max_problems = 100);

struct DamageScan {
  int64_t readable = 0;          // rows read whole with a valid checksum
  std::vector<SetKey> damaged;   // keys whose row cannot be read or fails its checksum
  // Rows of the table that could not be reached at all: their keys are
  // unknown unless an index still names them (then they are in `damaged`).
  int64_t unreachable_ranges = 0;
  std::vector<std::string> problems;  // what went wrong, one line each (the first 100)
};

// Reads every row of the cache at `path` that can be reached, on a
// read-only connection, and calls `on_readable` with each one that is whole
// and checksum-valid. Damaged pages do not stop it:
// - the keys come from three places that live on different pages: both
//   indexes of the `sets` table (their B-trees hold the key columns) and the
//   table itself, scanned in rowid order;
// - when the table scan hits a damaged page it skips ahead, probing for the
//   first rowid past the damage (doubling, then bisecting), and goes on;
// - every key found is then read by its rowid; one that cannot be read, or
//   whose blob fails its checksum, is listed as damaged.
// An error only when the file's schema itself cannot be read.
StatusOr<DamageScan> ScanForDamage(const std::string& path,
                                   const std::function<void(SetRecord&&)>& on_readable = nullptr);

struct RecoverReport {
  int64_t recovered = 0;
  std::vector<SetKey> lost;  // damaged: not copied
  std::vector<std::string> problems;
};

// Copies every readable, checksum-valid set of `damaged_path` into a new
// cache file at `out_path` (which must not exist), built as
// `out_path`.partial and renamed when complete. An existing .partial is
// refused unless `overwrite_partial` (it may be another run's work).
StatusOr<RecoverReport> RecoverCache(const std::string& damaged_path, const std::string& out_path,
                                     bool overwrite_partial = false);

}  // namespace alignset::storage

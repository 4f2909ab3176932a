#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/align/canonical.h"
#include "core/spectral/frequency_set.h"
#include "core/optimize/construction.h"
#include "core/optimize/optimizer.h"
#include "core/optimize/realization.h"
#include "core/util/point_set.h"
#include "core/util/status.h"

namespace alignset::storage {

// Bumped whenever the optimizer's output for the same parameters changes.
// 3: the low-frequency levers (weighted loss, axis clamp, projection, wider K).
// 4: up to N = 4096 the descent asks the engine for 1e-8 instead of 1e-11
//    (the same path, faster; DefaultEngineTolerance).
// 5: 1e-7 there (kernel width 8: the same sets within seed noise, faster).
// 6: keys that are not roots of the key lineage continue from their parent's
//    set for a short descent (core/align/key_lineage.h; WarmStartOptions).
// 7: the fast engine's FFTs are pruned to the modes' box (NufftGrid): the
//    same sums in another order, so the sets differ from version 6's in the
//    last bits (up to 1e-13 after a descent), not in quality.
// 8: warm descents above N = 32768 run without the warm-up share
//    (warm_warmup_max_points); the sets at N <= 32768 are version 7's bytes.
// 9: two-direction warm descents up to N = 4096 start with twice the default
//    step (warm_pair_learning_rate_scale); every other set is version 8's.
inline constexpr int kAlgorithmVersion = 9;

// Identifies how a set was made: every optimization parameter and the
// algorithm version, hashed into a short stable hex id. A changed parameter
// gives a new profile, so a stale set is never returned.
std::string ProfileId(const FrequencyParams& params, const OptimizerOptions& options,
                      uint64_t seed, int algorithm_version = kAlgorithmVersion);

// The profile a key of N points made by `construction` is cached under: a
// construction's own fixed profile, or for the optimized sets the ProfileId
// of N's default frequency set under the optimizer's options and seed (the
// server's, or what `export` is told the server runs). The one place the
// profile of a key is derived.
std::string KeyProfile(uint32_t n, const Construction& construction, const OptimizerOptions& options,
                       uint64_t seed);

// Primary key of a cached canonical set.
struct SetKey {
  uint32_t n = 0;
  CanonicalDirections dirs;
  std::string profile;
  // Which of the key's independent sets (core/optimize/realization.h); 0 is
  // the one every key always had.
  uint32_t realization = 0;
  friend bool operator==(const SetKey&, const SetKey&) = default;
};

// Checks a key at the boundary: n in [kMinPoints, kMaxPoints]; count 1 with
// phi1 in [0, 45], phi2 == phi1 and a quarter of 0..3 (0 at 45), or count 2
// with 0 <= phi1 <= phi2 < 180 in whole degrees; profile 1..64 characters of
// [A-Za-z0-9._-]; realization <= kMaxRealization.
Status ValidateKey(const SetKey& key);
// "n=4096 dirs=1:30 profile=0123456789abcdef" ("dirs=1:30.25" on the
// quarter-degree grid), for messages and logs; a realization r > 0 adds
// " r=R" before the profile.
std::string KeyToString(const SetKey& key);

struct SetRecord {
  SetKey key;
  PointSet points;  // the canonical (unaligned) set
  LossTerms loss;
  int iterations = 0;
  double optimize_seconds = 0.0;
  std::string engine;
  int64_t created_unix = 0;
  int algorithm_version = kAlgorithmVersion;
};

// A record without its points, for listings (reads no blob).
struct SetSummary {
  SetKey key;
  LossTerms loss;
  int iterations = 0;
  double optimize_seconds = 0.0;
  std::string engine;
  int64_t created_unix = 0;
  int algorithm_version = 0;
  int64_t bytes = 0;  // blob size
};

struct CacheStats {
  // True when the file has damaged pages: the figures then count the rows
  // that could still be read (storage/cache_recovery.h).
  bool damaged = false;
  int64_t sets = 0;
  int64_t bytes = 0;  // sum of blob sizes
  int64_t one_direction_sets = 0;
  int64_t two_direction_sets = 0;
};

struct VerifyReport {
  int64_t checked = 0;           // rows found (readable or not)
  std::vector<SetKey> corrupt;   // unreadable, or failing their checksum
  std::vector<std::string> problems;  // what SQLite said, one line each
};

// Where the file's pages go (PRAGMA page_size, page_count, freelist_count):
// the file is page_size * page_count bytes, of which the free pages hold
// nothing (they are reused by later writes, or returned by a vacuum).
struct FileSpace {
  int64_t page_size = 0;
  int64_t page_count = 0;
  int64_t freelist_count = 0;
  int64_t file_bytes() const { return page_size * page_count; }
  int64_t used_bytes() const { return page_size * (page_count - freelist_count); }
};

struct MergeReport {
  int64_t added = 0;
  int64_t skipped_existing = 0;
  int64_t skipped_corrupt = 0;
};

// The SQLite cache of canonical sets: WAL mode, busy timeout, schema version
// table with migrations, one transaction per written set, a checksum over
// every blob verified on read. Thread-safe (one connection behind a mutex;
// Verify and MergeFrom's source reads use their own read-only connections).
class SetCache {
 public:
  struct Options {
    bool read_only = false;
    // Also immutable (implies read_only): opened as the SQLite URI
    // file:PATH?mode=ro&immutable=1, so no lock is taken, no -wal / -shm file
    // is read or made, and the file is never written. For a shipped cache
    // file that nothing writes while it is served (a read-only replica); a
    // file that is still being written must not be opened this way.
    bool immutable = false;
    int busy_timeout_ms = 5000;
    // synchronous=FULL instead of NORMAL: also survives power loss without
    // losing the last commits (a process crash loses nothing either way).
    bool full_sync = false;
  };
  static StatusOr<std::unique_ptr<SetCache>> Open(const std::string& path, const Options& options);
  static StatusOr<std::unique_ptr<SetCache>> Open(const std::string& path) {
    return Open(path, Options{});
  }
  virtual ~SetCache() = default;

  // Inserts or replaces the record in one transaction.
  virtual Status Put(const SetRecord& record) = 0;
  // NotFound on a miss; DataLoss when the stored blob fails its checksum
  // (callers treat that as a miss and recompute; Put replaces the row).
  virtual StatusOr<SetRecord> Get(const SetKey& key) = 0;
  // Presence only: reads no blob and so does not verify it (Get does).
  virtual StatusOr<bool> Contains(const SetKey& key) = 0;
  // Keys (optionally for one N / one profile), in (n, count, phi1, phi2,
  // realization) order.
  virtual StatusOr<std::vector<SetKey>> List(std::optional<uint32_t> n = std::nullopt,
                                             std::optional<std::string> profile = std::nullopt) = 0;
  // Like List, with each row's metadata. The default implementation is built
  // on List + Get (so fakes need not override it); SQLite reads no blob.
  virtual StatusOr<std::vector<SetSummary>> ListSummaries(
      std::optional<uint32_t> n = std::nullopt, std::optional<std::string> profile = std::nullopt);
  virtual StatusOr<CacheStats> Stats() = 0;
  // Re-reads every row it can reach and checks its checksum; damaged pages
  // are reported (their keys in `corrupt` when an index still names them),
  // not fatal (ScanForDamage).
  virtual StatusOr<VerifyReport> Verify() = 0;
  // Copies every verified set of `other_path` that this cache lacks.
  virtual StatusOr<MergeReport> MergeFrom(const std::string& other_path) = 0;
  // Writes a consistent copy of this cache to `path` (which must not exist).
  virtual Status ExportTo(const std::string& path) = 0;
  // Whether a write can be committed now: rewrites one header field with
  // its own value in a committed transaction (no row changes). Fails when
  // the file is read-only (permissions, a read-only file system, a format
  // this SQLite may only read), locked past the busy timeout, or the disk is
  // full.
  virtual Status ProbeWrite() = 0;

  // For a bounded file (the server's --max-cache-bytes). The defaults say
  // the cache cannot do it (fakes need not).
  // Removes one set in one transaction; NotFound when it is not there.
  virtual Status Delete(const SetKey& key);
  virtual StatusOr<FileSpace> Space();
  // Makes later deletions returnable to the file system a little at a time
  // (PRAGMA auto_vacuum = INCREMENTAL). A file made without it is rebuilt
  // once by VACUUM (on its own connection, so reads go on meanwhile).
  virtual Status EnableIncrementalVacuum();
  // Returns at most `pages` free pages to the file system, in one short
  // transaction (PRAGMA incremental_vacuum); the free pages left after it.
  virtual StatusOr<int64_t> IncrementalVacuum(int64_t pages);
};

}  // namespace alignset::storage

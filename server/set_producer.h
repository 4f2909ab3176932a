#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "core/optimize/construction.h"
#include "core/optimize/lattice_term_cache.h"
#include "core/optimize/optimizer.h"
#include "server/cache_evictor.h"
#include "server/canonical_entry.h"
#include "server/metrics.h"
#include "server/set_lru.h"
#include "storage/set_cache.h"

namespace alignset::server {

// The keys a job optimizes, from the first whose parent is at hand (or a
// root) down to the key asked for, and the aligned start of the first.
struct LineagePlan {
  std::vector<storage::SetKey> chain;  // root-most first; the key asked for last
  std::optional<PointSet> warm_start;
  int iterations_total = 0;  // the budgets of the whole chain
};

// Where a key's set comes from, apart from who waits for it and when it runs
// (that is the Scheduler's queue): the memory LRU, the SQLite cache, the
// constructions (Construction::Build), the writer of a read-only replica
// (--fill-from), the optimizer with its key lineage; and storing a finished
// set, within the cache file's bound. Thread-safe: the scheduler's workers
// and its request threads call it at once, and it holds no scheduler lock.
class SetProducer {
 public:
  struct Options {
    OptimizerOptions optimizer;
    uint64_t seed = 1;
    int threads_per_worker = 0;
    size_t memory_cache_bytes = size_t{512} << 20;
    size_t lattice_terms_bytes = size_t{128} << 20;
    std::function<void(const Status&)> on_write_error;
    bool read_only = false;
    std::function<StatusOr<storage::SetRecord>(const storage::SetKey&, const std::function<bool()>&)> fill;
    int64_t max_cache_bytes = 0;
    // With max_cache_bytes: where the eviction order is kept between starts
    // (the cache file's path + ".served"; empty: not kept).
    std::string eviction_order_file;
    // With max_cache_bytes: a set that must not be evicted (its key is
    // being produced).
    std::function<bool(const std::string&)> pinned;
  };

  // Starts the evictor when the file is bounded.
  static StatusOr<std::unique_ptr<SetProducer>> Create(const Options& options, storage::SetCache* cache,
                                                       Metrics* metrics);

  // The key of N points with canonical directions `dirs`: an optimized set
  // under this server's optimization profile, a constructed one under its
  // construction's profile (core/optimize/construction.h).
  storage::SetKey KeyFor(uint32_t n, const CanonicalDirections& dirs, uint32_t realization = 0,
                         ConstructionKind construction = ConstructionKind::kOptimized) const;
  std::string ProfileFor(uint32_t n, ConstructionKind construction = ConstructionKind::kOptimized) const;

  // The set from memory, counted as a memory hit (and, with `touch`, as a
  // use for the evictor); null when memory does not hold it.
  std::shared_ptr<const CanonicalEntry> FromMemory(const std::string& name, const storage::SetKey& key,
                                                   bool touch);
  // The set from SQLite, then kept in memory; counted as a hit. Otherwise
  // the read's status: NOT_FOUND, DATA_LOSS for a row failing its checksum,
  // or the error.
  StatusOr<std::shared_ptr<const CanonicalEntry>> FromCache(const std::string& name, const storage::SetKey& key);
  // Whether the set is stored (checksum verified): precompute's skip test.
  StatusOr<bool> IsStored(const storage::SetKey& key);

  // A constructed key's set, built and stored; `seconds` gets the time.
  StatusOr<std::shared_ptr<const CanonicalEntry>> Construct(const std::string& name, const storage::SetKey& key,
                                                            double* seconds);
  // A replica's set from its writer, kept in memory only; CANCELLED when
  // `cancelled` turned true while the writer was asked.
  StatusOr<std::shared_ptr<const CanonicalEntry>> Fill(const std::string& name, const storage::SetKey& key,
                                                       const std::function<bool()>& cancelled);

  // The parent in the key lineage (core/align/key_lineage.h) an optimized
  // key warm-starts from; nullopt for a root, a constructed key, N below
  // --warm-min-n or a warm budget of 0.
  std::optional<storage::SetKey> LineageParentKey(const storage::SetKey& key) const;
  // The ancestors of `key` that must be optimized first (none held in memory
  // or in the cache), and the start of the first when its parent is held.
  LineagePlan PlanLineage(const std::string& name, const storage::SetKey& key);
  // The optimizer run for `target` (from `warm_start`, aligned, when given),
  // one key of job `name`'s lineage.
  StatusOr<std::unique_ptr<OptimizerRun>> StartOptimization(const std::string& name, const storage::SetKey& target,
                                                            std::optional<PointSet> warm_start,
                                                            const std::string& engine_name);

  // A finished set: stamped, stored (when it can be), counted, and put in
  // memory; the entry every waiter of the key gets.
  std::shared_ptr<const CanonicalEntry> Complete(const std::string& name, storage::SetRecord record);

  const Options& options() const { return options_; }

  // What its in-memory caches hold against their bounds (GetMetrics).
  struct MemoryUse {
    size_t sets_bytes = 0, sets_capacity = 0;        // the LRU of decoded sets
    size_t lattice_bytes = 0, lattice_capacity = 0;  // lattice search terms
  };
  MemoryUse memory() const;

 private:
  SetProducer(const Options& options, storage::SetCache* cache, Metrics* metrics);
  std::optional<PointSet> HeldSet(const storage::SetKey& key);
  // Writes a finished set (a writer), making room first when the file is
  // bounded; false when it was not stored.
  bool Store(const storage::SetRecord& record, const std::string& name);

  const Options options_;
  storage::SetCache* cache_;
  Metrics* metrics_;
  SetLru lru_;
  LatticeTermCache lattice_terms_;
  std::unique_ptr<CacheEvictor> evictor_;  // with max_cache_bytes only
  mutable std::mutex profile_mu_;
  mutable std::map<uint32_t, std::string> profiles_;
};

}  // namespace alignset::server

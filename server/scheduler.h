#pragma once

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <set>
#include <string>
#include <thread>
#include <tuple>
#include <vector>

#include "core/optimize/optimizer.h"
#include "core/spectral/spectral_engine.h"
#include "server/canonical_entry.h"
#include "server/metrics.h"
#include "server/set_lru.h"
#include "storage/set_cache.h"

namespace alignset::server {

// Interactive requests (GetAlignedSet, WatchAlignedSet) run before batch
// precompute; within a priority, first come first served.
enum class Priority { kInteractive = 0, kBatch = 1 };

struct JobView {
  enum class State { kQueued, kRunning, kDone };
  State state = State::kDone;
  size_t queue_position = 0;  // while queued: jobs ahead of it
  ProgressInfo progress;      // while running: the last progress callback
  double elapsed_seconds = 0.0;  // since it started running
  uint64_t version = 0;          // changes whenever anything above does
};

class Scheduler;
struct Job;

// One waiter's claim on a canonical set: either ready at once (a cache hit)
// or a share in the one optimization of its key. Destroying the ticket
// withdraws the waiter (see Scheduler for what that does to the job).
class Ticket {
 public:
  ~Ticket();
  Ticket(const Ticket&) = delete;
  Ticket& operator=(const Ticket&) = delete;

  // True once the set exists or its job ended without one.
  bool Done() const;
  // Waits at most `timeout` for Done().
  bool Wait(std::chrono::milliseconds timeout) const;
  // Waits at most `timeout` for the job to change past `version`.
  JobView WaitForChange(uint64_t version, std::chrono::milliseconds timeout) const;
  JobView View() const;
  // After Done(): the set, or why there is none.
  StatusOr<std::shared_ptr<const CanonicalEntry>> Result() const;
  // True when no optimization ran for this ticket (memory or SQLite hit).
  bool from_cache() const;

 private:
  friend class Scheduler;
  Ticket(Scheduler* scheduler, std::shared_ptr<Job> job, std::shared_ptr<const CanonicalEntry> ready)
      : scheduler_(scheduler), job_(std::move(job)), ready_(std::move(ready)) {}
  Scheduler* scheduler_;
  std::shared_ptr<Job> job_;                     // null for a hit
  std::shared_ptr<const CanonicalEntry> ready_;  // set for a hit
};

// Turns "I need the canonical set for this key" into at most one optimization
// per key, on a bounded pool of workers.
//
// Single flight: all tickets for a key that is queued or running share its one
// job. The waiter rule: a job lives while at least one ticket holds it (an
// interactive request, a watch stream, or a precompute stream for its batch
// item). When the last ticket goes (its client cancelled, hit its deadline or
// disconnected), a queued job leaves the queue, and a running one is stopped
// at its optimizer's next progress callback (which returns false); nothing is
// stored for it. A later request for the key starts afresh.
//
// Priority: interactive before batch; a batch job that an interactive request
// joins is promoted (keeping its place in arrival order). The queue is bounded: a request that would add a job to
// a full queue gets RESOURCE_EXHAUSTED (joining an existing job always works).
//
// Every finished set is stored in SQLite in one transaction (SetCache::Put)
// before any waiter sees it, then kept decoded in an in-memory LRU.
class Scheduler {
 public:
  struct Options {
    int workers = 1;
    int threads_per_worker = 0;
    EngineKind engine = EngineKind::kAuto;
    int max_queue = 256;
    OptimizerOptions optimizer;
    uint64_t seed = 1;
    size_t memory_cache_bytes = size_t{512} << 20;
    // Makes each worker's engine; unset: MakeSpectralEngine(engine,
    // threads_per_worker). Tests put an engine here that they can hold.
    std::function<StatusOr<std::unique_ptr<SpectralEngine>>()> engine_factory;
  };

  // Makes one spectral engine per worker up front, so a missing engine is a
  // start-up error rather than a failed request.
  static StatusOr<std::unique_ptr<Scheduler>> Create(const Options& options,
                                                     storage::SetCache* cache, Metrics* metrics);
  ~Scheduler();

  // The key of N points with canonical directions `dirs` under this server's
  // optimization profile; `realization` picks one of the key's independent
  // sets (optimized from RealizationSeed(seed, realization)).
  storage::SetKey KeyFor(uint32_t n, const CanonicalDirections& dirs,
                         uint32_t realization = 0) const;
  std::string ProfileFor(uint32_t n) const;
  const Options& options() const { return options_; }

  // A hit (memory, then SQLite), else a share in the key's job, queued if new.
  // A row failing its checksum is logged, counted and treated as a miss.
  StatusOr<std::unique_ptr<Ticket>> Acquire(const storage::SetKey& key, Priority priority);
  // Whether the set is stored (no decode, no checksum): precompute's skip test.
  StatusOr<bool> IsStored(const storage::SetKey& key);

  // Stops taking work: queued jobs end with UNAVAILABLE, running ones are
  // asked to stop at their next progress callback. A write in progress
  // finishes. Returns at once.
  void BeginShutdown();
  // BeginShutdown, then waits for the workers.
  void Shutdown();

  uint32_t queue_length() const;
  uint32_t running() const;

 private:
  friend class Ticket;
  Scheduler(const Options& options, storage::SetCache* cache, Metrics* metrics);
  void WorkerLoop(SpectralEngine* engine);
  void RunJob(const std::shared_ptr<Job>& job, SpectralEngine* engine);
  void Release(const std::shared_ptr<Job>& job);
  void FinishLocked(const std::shared_ptr<Job>& job);
  std::unique_ptr<Ticket> Ready(std::shared_ptr<const CanonicalEntry> entry) {
    return std::unique_ptr<Ticket>(new Ticket(this, nullptr, std::move(entry)));
  }

  const Options options_;
  storage::SetCache* cache_;
  Metrics* metrics_;
  SetLru lru_;
  std::vector<std::unique_ptr<SpectralEngine>> engines_;
  std::vector<std::thread> workers_;

  mutable std::mutex mu_;
  std::condition_variable work_cv_;
  bool stopping_ = false;
  uint64_t next_seq_ = 0;
  uint32_t running_ = 0;
  // (priority, arrival) -> job: begin() runs next.
  std::set<std::tuple<int, uint64_t, Job*>> queue_;
  std::map<std::string, std::shared_ptr<Job>> inflight_;
  mutable std::mutex profile_mu_;
  mutable std::map<uint32_t, std::string> profiles_;
};

}  // namespace alignset::server

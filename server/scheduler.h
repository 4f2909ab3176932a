#pragma once

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <set>
#include <string>
#include <thread>
#include <tuple>
#include <vector>

#include "core/optimize/construction.h"
#include "core/optimize/optimizer.h"
#include "core/spectral/spectral_engine.h"
#include "server/canonical_entry.h"
#include "server/metrics.h"
#include "server/set_producer.h"
#include "storage/set_cache.h"

namespace alignset::server {

// Interactive requests (GetAlignedSet, WatchAlignedSet) run before batch
// precompute; within a priority, clients take turns (see Scheduler).
enum class Priority { kInteractive = 0, kBatch = 1 };

struct JobView {
  enum class State { kQueued, kRunning, kDone };
  State state = State::kDone;
  size_t queue_position = 0;  // while queued: jobs that will run before it
  bool paused = false;        // queued again after running a slice
  ProgressInfo progress;      // since it first ran: the last progress callback
  double elapsed_seconds = 0.0;  // since it first started running
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
  // Runs `fn` once the ticket is done: at once (in this thread) when it
  // already is, else in the thread that finishes the job, outside the
  // scheduler's lock. Not called once the ticket is destroyed. At most one
  // per ticket. For waiters that hold no thread (the callback API).
  void OnDone(std::function<void()> fn);

 private:
  friend class Scheduler;
  Ticket(Scheduler* scheduler, std::shared_ptr<Job> job, std::shared_ptr<const CanonicalEntry> ready)
      : scheduler_(scheduler), job_(std::move(job)), ready_(std::move(ready)) {}
  Scheduler* scheduler_;
  std::shared_ptr<Job> job_;                     // null for a hit
  std::shared_ptr<const CanonicalEntry> ready_;  // set for a hit
};

// Turns "I need the canonical set for this key" into at most one optimization
// per key, on a bounded pool of workers shared fairly between clients.
//
// Single flight: all tickets for a key that is queued or running share its one
// job. The waiter rule: a job lives while at least one ticket holds it (an
// interactive request, a watch stream, or a precompute stream for its batch
// item). When the last ticket goes (its client cancelled, hit its deadline or
// disconnected), a queued job leaves the queue, and a running one is stopped
// at its optimizer's next progress callback; nothing is stored for it. A
// later request for the key starts afresh.
//
// Priority: interactive before batch; a batch job that an interactive request
// joins is promoted (keeping its place in arrival order).
//
// Fairness: a job belongs to the client that created it (the service names
// a client by its connection). Each client with work has a service account,
// the seconds its jobs have run on a worker; a client that arrives starts
// level with the least-served client already there (so reconnecting earns
// nothing). Within a priority the next job comes from the least-served
// client, and within one client jobs run in arrival order. A running job
// yields its worker, at a progress callback (every iteration), when work of
// a higher priority is waiting, or when another client with work of its
// priority waiting has been served at least `time_slice` less than its own
// client (the time slice is the granularity that keeps two long-running
// clients from switching every iteration). A job that yields is paused with
// its whole state (OptimizerRun) and goes back to the queue; when it is
// picked again it resumes where it stopped, and its set is bit for bit the
// one an uninterrupted run makes. At most `max_paused` jobs are held paused
// (their state is about 80 bytes a point); at that bound no job yields until
// a paused one has resumed. So a client that asks for a small set while
// another keeps the workers busy waits at most one time slice (plus one
// iteration of the job it displaces) before its job runs, and then runs for
// at least two time slices before it can be displaced in turn, however much
// the other client queued. Clients that open many connections get a share
// per connection (within --max-queue); --max-queue-per-client bounds each.
//
// Bounds: `max_queue` waiting jobs in all, `max_queue_per_client` per client;
// a request that would add a job past either gets RESOURCE_EXHAUSTED
// (joining an existing job always works).
//
// Where a set comes from and where it goes is the SetProducer's
// (server/set_producer.h): every finished set is stored in SQLite in one
// transaction (SetCache::Put) before any waiter sees it, then kept decoded in
// an in-memory LRU.
//
// A key with a construction's profile (core/optimize/construction.h) is a
// job like any other (single flight, queue, priority, bounds, metrics: it
// counts as an optimization), but its one slice builds the set instead of
// running the optimizer: it never pauses, and once running it finishes and
// is stored even when its waiters have left. The lattice searches share
// their per-direction terms (lattice_terms_bytes), so a key's realizations
// and the keys of a space cost what one batch would.
class Scheduler {
 public:
  struct Options {
    int workers = 1;
    EngineKind engine = EngineKind::kAuto;
    int max_queue = 256;
    int max_queue_per_client = 64;
    std::chrono::milliseconds time_slice{500};
    int max_paused = 16;
    // Where sets come from and go (the optimizer, the seed, the memory and
    // lattice-term bounds, a replica's fill, the file's bound): the
    // producer's own options, handed to it whole. Its threads_per_worker is
    // each worker engine's too. Its `pinned` is the scheduler's to set.
    SetProducer::Options producer;
    // Makes each worker's engine; unset: MakeSpectralEngine(engine,
    // threads_per_worker). Tests put an engine here that they can hold.
    std::function<StatusOr<std::unique_ptr<SpectralEngine>>()> engine_factory;
  };

  // Makes one spectral engine per worker up front, so a missing engine is a
  // start-up error rather than a failed request.
  static StatusOr<std::unique_ptr<Scheduler>> Create(const Options& options,
                                                     storage::SetCache* cache, Metrics* metrics);
  ~Scheduler();

  // Keys, profiles, what is stored and the memory in use are the producer's
  // (server/set_producer.h): the scheduler only decides when a key's set is
  // made.
  SetProducer& producer() const { return *producer_; }
  const Options& options() const { return options_; }

  // A hit (memory, then SQLite), else a share in the key's job, queued if new
  // and owned by `client`. A row failing its checksum is logged, counted and
  // treated as a miss.
  StatusOr<std::unique_ptr<Ticket>> Acquire(const storage::SetKey& key, Priority priority,
                                            const std::string& client = "");
  // Stops taking work: queued jobs end with UNAVAILABLE, running ones are
  // asked to stop at their next progress callback. A write in progress
  // finishes. Returns at once.
  void BeginShutdown();
  // BeginShutdown, then waits for the workers.
  void Shutdown();

  // Whether a call waits for this key's job now (queued or running).
  bool InFlight(const std::string& key_name) const;
  uint32_t queue_length() const;
  uint32_t running() const;
  uint32_t paused() const;
  // Calls `until(queue_length, running, paused)` now and at every change of
  // the three, in the thread that changes them and under the scheduler's
  // lock (so it sees every value they pass through, and must be quick and
  // call nothing of the scheduler), until it returns true or `timeout`
  // passes; returns whether it did. For callers that wait for the queue to
  // reach a state (a drain, a test) without polling.
  bool WaitForCounts(const std::function<bool(uint32_t queued, uint32_t running, uint32_t paused)>& until,
                     std::chrono::milliseconds timeout) const;

 private:
  friend class Ticket;
  // A client's service account and waiting jobs, per priority, in arrival
  // order.
  struct ClientQueue {
    double used = 0.0;  // seconds its jobs have run on a worker (slices ended)
    std::set<Job*> running;  // their current slices count too (ServedLocked)
    std::set<std::pair<uint64_t, Job*>> waiting[2];
    int jobs = 0;  // waiting or running: the entry goes when it reaches 0
  };
  using Callbacks = std::vector<std::function<void()>>;
  enum class SliceEnd { kDone, kPaused };

  Scheduler(const Options& options, Metrics* metrics);
  void WorkerLoop(SpectralEngine* engine);
  SliceEnd RunSlice(const std::shared_ptr<Job>& job, SpectralEngine* engine, bool engine_holds_k);
  // An optimized key's slice: its lineage planned on the first, then the
  // optimizer resumed until it pauses, is cancelled or finishes a key.
  SliceEnd OptimizeSlice(const std::shared_ptr<Job>& job, SpectralEngine* engine, bool engine_holds_k);
  // Hands the job's outcome to its waiters.
  SliceEnd Finish(const std::shared_ptr<Job>& job, const Status& status,
                  std::shared_ptr<const CanonicalEntry> entry);
  void Release(const std::shared_ptr<Job>& job, const Ticket* ticket);
  // mu_ held; what the job's waiters asked to run goes into `callbacks`.
  void FinishLocked(const std::shared_ptr<Job>& job, Callbacks* callbacks);
  void EnqueueLocked(Job* job);
  void DequeueLocked(Job* job);
  void LeaveClientLocked(Job* job);
  Job* PickLocked();
  // The client's service so far, its running slices included.
  double ServedLocked(const ClientQueue& q, std::chrono::steady_clock::time_point now) const;
  // Which of two clients with waiting work at priority `c` goes first.
  bool BeforeLocked(const ClientQueue& a, const ClientQueue& b, int c,
                    std::chrono::steady_clock::time_point now) const;
  bool ShouldYieldLocked(const Job& job, std::chrono::steady_clock::time_point now) const;
  size_t PositionLocked(const Job& job) const;
  std::unique_ptr<Ticket> Ready(std::shared_ptr<const CanonicalEntry> entry) {
    return std::unique_ptr<Ticket>(new Ticket(this, nullptr, std::move(entry)));
  }

  const Options options_;
  Metrics* metrics_;
  std::unique_ptr<SetProducer> producer_;
  std::vector<std::unique_ptr<SpectralEngine>> engines_;
  std::vector<std::thread> workers_;

  mutable std::mutex mu_;
  std::condition_variable work_cv_;
  bool stopping_ = false;
  uint64_t next_seq_ = 0;
  uint32_t running_ = 0;
  uint32_t paused_ = 0;
  size_t waiting_[2] = {0, 0};  // waiting jobs per priority, all clients
  std::map<std::string, ClientQueue> clients_;
  std::map<std::string, std::shared_ptr<Job>> inflight_;
  // WaitForCounts' callers: each predicate is asked at every change of
  // running_, paused_ or waiting_ (CountsChangedLocked).
  struct CountsWaiter {
    const std::function<bool(uint32_t, uint32_t, uint32_t)>* until;
    bool met = false;
  };
  mutable std::vector<CountsWaiter*> counts_waiters_;
  mutable std::condition_variable counts_cv_;
  void CountsChangedLocked();
};

}  // namespace alignset::server

#include "server/scheduler.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <ctime>
#include <iterator>

#include "core/align/key_lineage.h"
#include "core/optimize/aligned_lattice.h"
#include "core/optimize/aligned_net.h"
#include "core/optimize/realization.h"

namespace alignset::server {

using Clock = std::chrono::steady_clock;

// Everything in a Job is guarded by Scheduler::mu_, except `run` while the
// job is running: then only its worker touches it.
struct Job {
  storage::SetKey key;
  std::string name;    // KeyString(key), for the maps and the logs
  std::string client;  // who created it: the fairness between clients
  int priority = 0;
  uint64_t seq = 0;
  int waiters = 0;
  JobView::State state = JobView::State::kQueued;
  bool paused = false;  // waiting again, with `run` holding its state
  ProgressInfo progress;
  bool ever_ran = false;
  Clock::time_point started;      // first slice
  Clock::time_point slice_start;  // current slice
  double run_seconds = 0.0;       // the slices so far
  uint64_t version = 0;
  // Set when the job was given up (no waiters left, or shutdown): it has
  // left `inflight_`, so a new request starts a new job.
  bool abandoned = false;
  std::condition_variable cv;
  Status status;
  std::shared_ptr<const CanonicalEntry> entry;
  bool from_cache = false;
  std::unique_ptr<OptimizerRun> run;
  std::map<const Ticket*, std::function<void()>> on_done;
  // The key lineage (core/align/key_lineage.h) this job optimizes, from the
  // first key whose parent is at hand (or a root) down to `key`; `chain_next`
  // is the one running or next. Ancestors are stored as they finish, like
  // any set, so the next key's lineage starts from them.
  std::vector<storage::SetKey> chain;
  size_t chain_next = 0;
  std::optional<PointSet> warm_start;  // the start of chain[chain_next], aligned
  int chain_iterations_done = 0;       // iterations of the finished chain members
  int chain_iterations_total = 0;      // the budgets of the whole chain
};

namespace {

// Logs the 1st, 2nd, 4th, 8th, ... occurrence: a flood of refusals cannot
// flood the log, and the count in the line says how many there were.
bool LogThisOne(uint64_t count) { return (count & (count - 1)) == 0; }

}  // namespace

// ---------------------------------------------------------------- Ticket

Ticket::~Ticket() {
  if (job_) scheduler_->Release(job_, this);
}

bool Ticket::Done() const {
  if (!job_) return true;
  std::lock_guard<std::mutex> lock(scheduler_->mu_);
  return job_->state == JobView::State::kDone;
}

bool Ticket::Wait(std::chrono::milliseconds timeout) const {
  if (!job_) return true;
  std::unique_lock<std::mutex> lock(scheduler_->mu_);
  return job_->cv.wait_for(lock, timeout, [&] { return job_->state == JobView::State::kDone; });
}

JobView Ticket::WaitForChange(uint64_t version, std::chrono::milliseconds timeout) const {
  if (job_) {
    std::unique_lock<std::mutex> lock(scheduler_->mu_);
    job_->cv.wait_for(lock, timeout, [&] { return job_->version != version; });
  }
  return View();
}

JobView Ticket::View() const {
  JobView v;
  if (!job_) return v;  // a hit is done from the start
  std::lock_guard<std::mutex> lock(scheduler_->mu_);
  v.state = job_->state;
  v.version = job_->version;
  v.progress = job_->progress;
  v.paused = job_->paused;
  if (job_->state == JobView::State::kQueued) v.queue_position = scheduler_->PositionLocked(*job_);
  if (job_->ever_ran) v.elapsed_seconds = std::chrono::duration<double>(Clock::now() - job_->started).count();
  return v;
}

StatusOr<std::shared_ptr<const CanonicalEntry>> Ticket::Result() const {
  if (!job_) return ready_;
  std::lock_guard<std::mutex> lock(scheduler_->mu_);
  if (job_->state != JobView::State::kDone) return Status::Unavailable("the set is not ready yet");
  if (!job_->status.ok()) return job_->status;
  return job_->entry;
}

bool Ticket::from_cache() const {
  if (!job_) return true;
  std::lock_guard<std::mutex> lock(scheduler_->mu_);
  return job_->from_cache;
}

void Ticket::OnDone(std::function<void()> fn) {
  if (job_) {
    std::lock_guard<std::mutex> lock(scheduler_->mu_);
    if (job_->state != JobView::State::kDone) {
      job_->on_done[this] = std::move(fn);
      return;
    }
  }
  fn();
}

// ------------------------------------------------------------- Scheduler

Scheduler::Scheduler(const Options& options, storage::SetCache* cache, Metrics* metrics)
    : options_(options),
      cache_(cache),
      metrics_(metrics),
      lru_(options.memory_cache_bytes),
      lattice_terms_(options.lattice_terms_bytes) {}

StatusOr<std::unique_ptr<Scheduler>> Scheduler::Create(const Options& options,
                                                       storage::SetCache* cache, Metrics* metrics) {
  if (options.workers < 1) return Status::InvalidArgument("workers must be at least 1");
  if (options.max_queue < 1) return Status::InvalidArgument("max_queue must be at least 1");
  if (options.max_queue_per_client < 1) return Status::InvalidArgument("max_queue_per_client must be at least 1");
  if (options.max_paused < 0) return Status::InvalidArgument("max_paused must be at least 0");
  if (options.time_slice.count() < 0) return Status::InvalidArgument("time_slice must be at least 0");
  if (Status s = ValidateOptions(options.optimizer); !s.ok()) return s;
  Options o = options;
  // A progress callback every iteration: it is where a job yields its worker
  // (fairness) and notices that its waiters left. It costs one uncontended
  // lock per iteration and does not change the set (progress_every is not
  // part of the profile).
  o.optimizer.progress_every = 1;
  if (o.read_only) o.max_cache_bytes = 0;
  std::unique_ptr<Scheduler> s(new Scheduler(o, cache, metrics));
  if (o.max_cache_bytes > 0) {
    metrics->max_cache_bytes = o.max_cache_bytes;
    CacheEvictor::Options eo;
    eo.max_bytes = o.max_cache_bytes;
    eo.pinned = [p = s.get()](const std::string& name) { return p->InFlight(name); };
    eo.evicted = [p = s.get()](const std::string& name) { p->lru_.Erase(name); };
    s->evictor_ = std::make_unique<CacheEvictor>(cache, metrics, std::move(eo));
    if (Status st = s->evictor_->Start(); !st.ok()) return st;
  }
  for (int i = 0; i < options.workers; ++i) {
    auto engine = options.engine_factory
                      ? options.engine_factory()
                      : MakeSpectralEngine(options.engine, options.threads_per_worker);
    if (!engine.ok()) return engine.status();
    s->engines_.push_back(std::move(engine).value());
  }
  for (auto& engine : s->engines_) {
    s->workers_.emplace_back([p = s.get(), e = engine.get()] { p->WorkerLoop(e); });
  }
  return s;
}

Scheduler::~Scheduler() { Shutdown(); }

std::string Scheduler::ProfileFor(uint32_t n, Construction construction) const {
  if (construction == Construction::kLattice) return kLatticeProfile;
  if (construction == Construction::kNet) return kNetProfile;
  if (construction == Construction::kTentLattice) return kTentLatticeProfile;
  std::lock_guard<std::mutex> lock(profile_mu_);
  auto it = profiles_.find(n);
  if (it != profiles_.end()) return it->second;
  std::string p = storage::ProfileId(DefaultFrequencyParams(n), options_.optimizer, options_.seed);
  profiles_.emplace(n, p);
  return p;
}

storage::SetKey Scheduler::KeyFor(uint32_t n, const CanonicalDirections& dirs,
                                  uint32_t realization, Construction construction) const {
  return storage::SetKey{n, dirs, ProfileFor(n, construction), realization};
}

StatusOr<bool> Scheduler::IsStored(const storage::SetKey& key) {
  const std::string name = KeyString(key);
  if (lru_.Get(name)) return true;
  // A full read, not Contains(): the checksum is verified, so a precompute
  // re-run recomputes a corrupt row instead of counting it as cached.
  StatusOr<storage::SetRecord> stored = cache_->Get(key);
  if (stored.ok()) return true;
  // A corrupt row is not stored; the Acquire() that follows reads it again,
  // and reports and counts it there (once).
  if (stored.status().code() == Status::Code::kNotFound ||
      stored.status().code() == Status::Code::kDataLoss) {
    return false;
  }
  return stored.status();
}

// ------------------------------------------------- the queue (mu_ held)

void Scheduler::EnqueueLocked(Job* job) {
  clients_[job->client].waiting[job->priority].insert({job->seq, job});
  ++waiting_[job->priority];
  if (job->paused) ++paused_;
}

void Scheduler::DequeueLocked(Job* job) {
  auto it = clients_.find(job->client);
  if (it == clients_.end() || it->second.waiting[job->priority].erase({job->seq, job}) == 0) return;
  --waiting_[job->priority];
  if (job->paused) --paused_;
}

void Scheduler::LeaveClientLocked(Job* job) {
  auto it = clients_.find(job->client);
  if (it != clients_.end() && --it->second.jobs <= 0) clients_.erase(it);
}

double Scheduler::ServedLocked(const ClientQueue& q, Clock::time_point now) const {
  double served = q.used;
  for (const Job* j : q.running) served += std::chrono::duration<double>(now - j->slice_start).count();
  return served;
}

bool Scheduler::BeforeLocked(const ClientQueue& a, const ClientQueue& b, int c, Clock::time_point now) const {
  // Less served first; on a tie, a client that is not running now; then the
  // older job.
  return std::make_tuple(ServedLocked(a, now), a.running.size(), a.waiting[c].begin()->first) <
         std::make_tuple(ServedLocked(b, now), b.running.size(), b.waiting[c].begin()->first);
}

Job* Scheduler::PickLocked() {
  const auto now = Clock::now();
  for (int c = 0; c < 2; ++c) {
    if (waiting_[c] == 0) continue;
    const ClientQueue* best = nullptr;
    for (const auto& [name, q] : clients_) {
      if (!q.waiting[c].empty() && (best == nullptr || BeforeLocked(q, *best, c, now))) best = &q;
    }
    return best->waiting[c].begin()->second;
  }
  return nullptr;
}

bool Scheduler::ShouldYieldLocked(const Job& job, Clock::time_point now) const {
  // At the bound no job yields until a paused one has resumed: the paused
  // states are what costs memory.
  if (paused_ >= static_cast<uint32_t>(options_.max_paused)) return false;
  for (int h = 0; h < job.priority; ++h) {
    if (waiting_[h] > 0) return true;  // interactive work waits behind a batch job
  }
  auto mine = clients_.find(job.client);
  if (mine == clients_.end()) return false;
  const double used = ServedLocked(mine->second, now);
  const double slice = std::chrono::duration<double>(options_.time_slice).count();
  for (const auto& [name, q] : clients_) {
    if (&q != &mine->second && !q.waiting[job.priority].empty() && ServedLocked(q, now) + slice <= used) {
      return true;
    }
  }
  return false;
}

// An estimate of where the job stands in the order PickLocked will take the
// waiting jobs: every job of a higher priority, then rounds in which each
// client with work runs one job, the least-served client first.
size_t Scheduler::PositionLocked(const Job& job) const {
  const int c = job.priority;
  size_t position = 0;
  for (int h = 0; h < c; ++h) position += waiting_[h];
  auto mine = clients_.find(job.client);
  if (mine == clients_.end()) return position;
  const auto& own = mine->second.waiting[c];
  auto at = own.find({job.seq, const_cast<Job*>(&job)});
  if (at == own.end()) return position;
  const size_t round = static_cast<size_t>(std::distance(own.begin(), at));
  const auto now = Clock::now();
  for (const auto& [name, q] : clients_) {
    if (&q == &mine->second || q.waiting[c].empty()) continue;
    const bool ahead = BeforeLocked(q, mine->second, c, now);
    position += std::min(q.waiting[c].size(), round + (ahead ? 1 : 0));
  }
  return position + round;
}

// ------------------------------------------------------------ requests

StatusOr<std::unique_ptr<Ticket>> Scheduler::Acquire(const storage::SetKey& key, Priority priority,
                                                     const std::string& client) {
  const std::string name = KeyString(key);
  if (auto hit = lru_.Get(name)) {
    metrics_->cache_hits_memory.fetch_add(1, std::memory_order_relaxed);
    if (evictor_) evictor_->Touch(name, key);
    return Ready(std::move(hit));
  }
  const int prio = static_cast<int>(priority);
  // Joins the key's job if there is one; mu_ held.
  auto join = [&](const std::shared_ptr<Job>& job) {
    ++job->waiters;
    if (job->state == JobView::State::kQueued && prio < job->priority) {
      DequeueLocked(job.get());
      job->priority = prio;
      EnqueueLocked(job.get());
      ++job->version;
    }
    metrics_->cache_misses.fetch_add(1, std::memory_order_relaxed);
    metrics_->shared_waits.fetch_add(1, std::memory_order_relaxed);
    return std::unique_ptr<Ticket>(new Ticket(this, job, nullptr));
  };
  {
    std::lock_guard<std::mutex> lock(mu_);
    if (stopping_) return Status::Unavailable("the server is shutting down");
    if (auto it = inflight_.find(name); it != inflight_.end()) return join(it->second);
  }
  // SQLite outside the lock: reads run concurrently with everything else.
  auto stored = cache_->Get(key);
  if (stored.ok()) {
    auto entry = std::make_shared<const CanonicalEntry>(std::move(stored).value());
    lru_.Put(name, entry);
    metrics_->cache_hits_db.fetch_add(1, std::memory_order_relaxed);
    if (evictor_) evictor_->Touch(name, key);
    return Ready(std::move(entry));
  }
  if (stored.status().code() == Status::Code::kDataLoss) {
    metrics_->corrupt_rows.fetch_add(1, std::memory_order_relaxed);
    spdlog::warn("corrupt row {}: {}; recomputing", name, stored.status().message());
  } else if (stored.status().code() != Status::Code::kNotFound) {
    spdlog::error("cache read {}: {}", name, stored.status().message());
    return Status::Unavailable("cache read failed: " + stored.status().message());
  }
  if (options_.read_only && !options_.fill) {
    const uint64_t n = metrics_->replica_misses.fetch_add(1, std::memory_order_relaxed) + 1;
    if (LogThisOne(n)) spdlog::info("read-only replica: no set {} ({} misses so far)", name, n);
    return Status::NotFound("read-only replica: " + name +
                            " is not in its cache file; precompute it into the shipped file, or "
                            "start the replica with --fill-from WRITER");
  }

  std::lock_guard<std::mutex> lock(mu_);
  if (stopping_) return Status::Unavailable("the server is shutting down");
  // Another request may have started (or finished) the job meanwhile.
  if (auto it = inflight_.find(name); it != inflight_.end()) return join(it->second);
  if (auto hit = lru_.Get(name)) {
    metrics_->cache_hits_memory.fetch_add(1, std::memory_order_relaxed);
    return Ready(std::move(hit));
  }
  const size_t waiting = waiting_[0] + waiting_[1];
  if (waiting >= static_cast<size_t>(options_.max_queue)) {
    const uint64_t n = metrics_->rejected_queue_full.fetch_add(1, std::memory_order_relaxed) + 1;
    if (LogThisOne(n)) spdlog::warn("queue full ({} waiting), rejected {} ({} so far)", waiting, name, n);
    return Status::ResourceExhausted("the optimization queue is full (" + std::to_string(waiting) +
                                     " waiting, --max-queue); retry later");
  }
  if (auto c = clients_.find(client); c != clients_.end()) {
    const size_t mine = c->second.waiting[0].size() + c->second.waiting[1].size();
    if (mine >= static_cast<size_t>(options_.max_queue_per_client)) {
      const uint64_t n = metrics_->rejected_client_limit.fetch_add(1, std::memory_order_relaxed) + 1;
      if (LogThisOne(n)) {
        spdlog::warn("client at its limit ({} waiting), rejected {} ({} so far)", mine, name, n);
      }
      return Status::ResourceExhausted("this client already has " + std::to_string(mine) +
                                       " optimizations waiting (--max-queue-per-client); retry when "
                                       "some have finished");
    }
  }
  auto job = std::make_shared<Job>();
  job->key = key;
  job->name = name;
  job->client = client;
  job->priority = prio;
  job->seq = next_seq_++;
  job->waiters = 1;
  inflight_.emplace(name, job);
  auto [entry, is_new] = clients_.try_emplace(client);
  if (is_new) {
    // A client that arrives starts level with the least-served one already
    // there: a new connection earns no credit over those that kept working.
    const auto now = Clock::now();
    bool first = true;
    for (const auto& [other, q] : clients_) {
      if (&q == &entry->second) continue;
      const double served = ServedLocked(q, now);
      entry->second.used = first ? served : std::min(entry->second.used, served);
      first = false;
    }
  }
  ++entry->second.jobs;
  EnqueueLocked(job.get());
  metrics_->cache_misses.fetch_add(1, std::memory_order_relaxed);
  spdlog::info("queued {} ({}, position {})", name,
               priority == Priority::kInteractive ? "interactive" : "batch", PositionLocked(*job));
  work_cv_.notify_one();
  return std::unique_ptr<Ticket>(new Ticket(this, job, nullptr));
}

void Scheduler::Release(const std::shared_ptr<Job>& job, const Ticket* ticket) {
  Callbacks callbacks;
  {
    std::lock_guard<std::mutex> lock(mu_);
    job->on_done.erase(ticket);
    if (--job->waiters > 0 || job->state != JobView::State::kQueued) return;
    // The last waiter left a job that is not running (queued, or paused
    // between slices): drop it. A running job notices at its next progress
    // callback.
    DequeueLocked(job.get());
    job->abandoned = true;
    job->status = Status::Cancelled("every waiter left");
    metrics_->optimizations_cancelled.fetch_add(1, std::memory_order_relaxed);
    spdlog::info("withdrawn {} (no waiters left {})", job->name,
                 job->paused ? "while it was paused" : "before it ran");
    FinishLocked(job, &callbacks);
  }
  for (auto& fn : callbacks) fn();
}

void Scheduler::FinishLocked(const std::shared_ptr<Job>& job, Callbacks* callbacks) {
  job->state = JobView::State::kDone;
  job->paused = false;
  job->run.reset();
  ++job->version;
  if (auto it = inflight_.find(job->name); it != inflight_.end() && it->second == job) {
    inflight_.erase(it);
  }
  LeaveClientLocked(job.get());
  job->cv.notify_all();
  for (auto& [ticket, fn] : job->on_done) callbacks->push_back(std::move(fn));
  job->on_done.clear();
}

// ------------------------------------------------------------- workers

void Scheduler::WorkerLoop(SpectralEngine* engine) {
  // The job whose frequency set this worker's engine holds: resuming it
  // right after its own slice skips setting K again.
  uint64_t engine_job = UINT64_MAX;
  for (;;) {
    std::shared_ptr<Job> job;
    {
      std::unique_lock<std::mutex> lock(mu_);
      work_cv_.wait(lock, [&] { return stopping_ || waiting_[0] + waiting_[1] > 0; });
      if (stopping_) return;
      Job* next = PickLocked();
      job = inflight_.at(next->name);
      DequeueLocked(job.get());
      job->paused = false;
      job->state = JobView::State::kRunning;
      const auto now = Clock::now();
      if (!job->ever_ran) {
        job->ever_ran = true;
        job->started = now;
      }
      job->slice_start = now;
      clients_[job->client].running.insert(job.get());
      ++job->version;
      ++running_;
      job->cv.notify_all();
    }
    const SliceEnd end = RunSlice(job, engine, engine_job == job->seq);
    engine_job = job->seq;
    Callbacks callbacks;
    {
      std::lock_guard<std::mutex> lock(mu_);
      --running_;
      if (auto c = clients_.find(job->client); c != clients_.end()) {
        c->second.used += std::chrono::duration<double>(Clock::now() - job->slice_start).count();
        c->second.running.erase(job.get());
      }
      if (end == SliceEnd::kPaused && job->waiters > 0 && !stopping_) {
        job->state = JobView::State::kQueued;
        job->paused = true;
        EnqueueLocked(job.get());
        ++job->version;
        job->cv.notify_all();
        work_cv_.notify_one();
      } else {
        if (end == SliceEnd::kPaused) {  // its waiters left (or shutdown) as it paused
          job->abandoned = true;
          job->status = stopping_ ? Status::Unavailable("the server is shutting down")
                                  : Status::Cancelled("every waiter left");
          metrics_->optimizations_cancelled.fetch_add(1, std::memory_order_relaxed);
        }
        FinishLocked(job, &callbacks);
      }
    }
    for (auto& fn : callbacks) fn();
  }
}

Scheduler::SliceEnd Scheduler::RunSlice(const std::shared_ptr<Job>& job, SpectralEngine* engine,
                                        bool engine_holds_k) {
  const storage::SetKey& key = job->key;
  if (!job->run) {
    // Another server process (or an earlier run) may have stored it by now.
    if (auto stored = cache_->Get(key); stored.ok()) {
      auto entry = std::make_shared<const CanonicalEntry>(std::move(stored).value());
      lru_.Put(job->name, entry);
      metrics_->cache_hits_db.fetch_add(1, std::memory_order_relaxed);
      if (evictor_) evictor_->Touch(job->name, key);
      std::lock_guard<std::mutex> lock(mu_);
      job->entry = std::move(entry);
      job->from_cache = true;
      return SliceEnd::kDone;
    }
    if (options_.fill) return FillSlice(job);
    if (const Construction c = ConstructionOfProfile(key.profile); c != Construction::kOptimized) {
      return ConstructedSlice(job, c);
    }
    if (job->chain.empty()) PlanLineage(job.get());
    const storage::SetKey& target = job->chain[job->chain_next];
    OptimizationProblem problem;
    problem.n = target.n;
    problem.directions = {Phi1Degrees(target.dirs)};
    if (target.dirs.count == 2) problem.directions.push_back(Phi2Degrees(target.dirs));
    problem.seed = RealizationSeed(options_.seed, target.realization);
    OptimizerOptions options = options_.optimizer;
    if (job->warm_start) {
      problem.start = std::move(*job->warm_start);
      job->warm_start.reset();
      options = WarmStartOptions(options_.optimizer, target.n, target.dirs.count);
    }
    auto run = OptimizerRun::Create(problem, options);
    if (!run.ok()) {
      metrics_->optimizations_failed.fetch_add(1, std::memory_order_relaxed);
      spdlog::error("optimize failed {}: {}", job->name, run.status().message());
      return Finish(job, Status::Internal("optimization failed: " + run.status().message()), nullptr);
    }
    {
      std::lock_guard<std::mutex> lock(mu_);
      job->run = std::move(run).value();
    }
    metrics_->optimizations_started.fetch_add(1, std::memory_order_relaxed);
    spdlog::info("optimize start {} engine={} max_iterations={}{}", KeyString(target), engine->name(),
                 EffectiveMaxIterations(options, target.n, target.dirs.count),
                 problem.start ? " (warm: from its parent)" : "");
  } else {
    spdlog::debug("optimize resume {} at iteration {}", job->name, job->run->iteration());
  }

  const auto t0 = Clock::now();
  const OptimizerRun::Outcome outcome =
      job->run->Resume(*engine, engine_holds_k, [&](const ProgressInfo& p) {
        std::lock_guard<std::mutex> lock(mu_);
        job->progress = p;
        // One bar for the whole lineage: its members' iterations add up.
        job->progress.iteration += job->chain_iterations_done;
        job->progress.max_iterations = std::max(job->chain_iterations_total, job->progress.iteration);
        ++job->version;
        job->cv.notify_all();
        if (job->waiters > 0 && !stopping_) {
          return ShouldYieldLocked(*job, Clock::now()) ? RunControl::kPause : RunControl::kContinue;
        }
        // Given up: leave inflight_ now so that a request arriving from here
        // on starts a new job instead of joining one that is stopping.
        job->abandoned = true;
        if (auto it = inflight_.find(job->name); it != inflight_.end() && it->second == job) {
          inflight_.erase(it);
        }
        return RunControl::kCancel;
      });
  job->run_seconds += std::chrono::duration<double>(Clock::now() - t0).count();
  if (outcome == OptimizerRun::Outcome::kPaused) {
    metrics_->optimizations_paused.fetch_add(1, std::memory_order_relaxed);
    spdlog::debug("optimize pause {} at iteration {} ({:.2f} s so far)", job->name, job->run->iteration(),
                  job->run_seconds);
    return SliceEnd::kPaused;
  }
  OptimizationResult result = job->run->TakeResult();
  const double seconds = job->run_seconds;

  Status status;
  std::shared_ptr<const CanonicalEntry> entry;
  bool abandoned, stopping;
  {
    std::lock_guard<std::mutex> lock(mu_);
    abandoned = job->abandoned;
    stopping = stopping_;
  }
  if (abandoned || result.stop_reason == StopReason::kCancelled) {
    metrics_->optimizations_cancelled.fetch_add(1, std::memory_order_relaxed);
    spdlog::info("optimize cancelled {} after {} iterations ({:.2f} s): {}", job->name,
                 result.iterations, seconds, stopping ? "shutdown" : "no waiters left");
    status = stopping ? Status::Unavailable("the server is shutting down")
                      : Status::Cancelled("every waiter left");
  } else {
    const storage::SetKey target = job->chain[job->chain_next];
    const std::string target_name = KeyString(target);
    storage::SetRecord record;
    record.key = target;
    record.points = std::move(result.points);
    record.loss = result.final_loss;
    record.iterations = result.iterations;
    record.optimize_seconds = seconds;
    record.engine = engine->name();
    spdlog::info("optimize done {} loss={:.6g} spectrum={:.6g} sw={:.6g} iterations={} {:.2f} s",
                 target_name, record.loss.total, record.loss.spectrum, record.loss.sw,
                 record.iterations, seconds);
    entry = Complete(target_name, std::move(record));
    if (job->chain_next + 1 < job->chain.size()) {
      // An ancestor: stored, and the start of the next key down the lineage.
      const storage::SetKey& child = job->chain[job->chain_next + 1];
      const auto parent = WarmParent(child.dirs);
      std::lock_guard<std::mutex> lock(mu_);
      job->warm_start = Align(entry->record().points, parent->ops);
      job->chain_iterations_done += result.iterations;
      ++job->chain_next;
      job->run.reset();
      job->run_seconds = 0.0;
      return SliceEnd::kPaused;
    }
  }
  return Finish(job, status, std::move(entry));
}

void Scheduler::PlanLineage(Job* job) {
  std::vector<storage::SetKey> chain = {job->key};
  std::optional<PointSet> start;
  // Up to a root (optimized from Owen-Sobol) or a stored ancestor.
  while (const auto parent_key = LineageParentKey(chain.back())) {
    if (auto points = HeldSet(*parent_key)) {
      start = Align(*points, WarmParent(chain.back().dirs)->ops);
      break;
    }
    chain.push_back(*parent_key);
  }
  std::reverse(chain.begin(), chain.end());
  int total = 0;
  for (size_t i = 0; i < chain.size(); ++i) {
    const bool warm = i > 0 || start.has_value();
    const OptimizerOptions o = warm ? WarmStartOptions(options_.optimizer, chain[i].n, chain[i].dirs.count)
                                    : options_.optimizer;
    total += EffectiveMaxIterations(o, chain[i].n, chain[i].dirs.count);
  }
  if (chain.size() > 1) {
    spdlog::info("lineage {}: {} key(s) to optimize first, from {}", job->name, chain.size() - 1,
                 start ? "a stored parent" : "a root");
  }
  std::lock_guard<std::mutex> lock(mu_);
  job->chain = std::move(chain);
  job->chain_next = 0;
  job->warm_start = std::move(start);
  job->chain_iterations_done = 0;
  job->chain_iterations_total = total;
}

std::optional<storage::SetKey> Scheduler::LineageParentKey(const storage::SetKey& key) const {
  if (ConstructionOfProfile(key.profile) != Construction::kOptimized ||
      !UsesKeyLineage(options_.optimizer, key.n)) {
    return std::nullopt;
  }
  const auto parent = WarmParent(key.dirs);
  if (!parent) return std::nullopt;
  storage::SetKey parent_key = key;
  parent_key.dirs = parent->parent;
  return parent_key;
}

std::optional<PointSet> Scheduler::HeldSet(const storage::SetKey& key) {
  const std::string name = KeyString(key);
  if (auto hit = lru_.Get(name)) return hit->record().points;
  if (auto stored = cache_->Get(key); stored.ok()) return std::move(stored->points);
  return std::nullopt;
}

std::shared_ptr<const CanonicalEntry> Scheduler::Complete(const std::string& name,
                                                          storage::SetRecord record) {
  record.created_unix = static_cast<int64_t>(std::time(nullptr));
  const bool stored = Store(record, name);
  metrics_->optimizations_completed.fetch_add(1, std::memory_order_relaxed);
  metrics_->RecordOptimization(record.optimize_seconds);
  auto entry = std::make_shared<const CanonicalEntry>(std::move(record), stored);
  lru_.Put(name, entry);
  return entry;
}

Scheduler::SliceEnd Scheduler::Finish(const std::shared_ptr<Job>& job, const Status& status,
                                      std::shared_ptr<const CanonicalEntry> entry) {
  std::lock_guard<std::mutex> lock(mu_);
  job->status = status;
  job->entry = std::move(entry);
  return SliceEnd::kDone;
}

bool Scheduler::Store(const storage::SetRecord& record, const std::string& name) {
  if (options_.read_only) {
    metrics_->sets_not_stored.fetch_add(1, std::memory_order_relaxed);
    return false;
  }
  if (evictor_) {
    // The key is still in inflight_ (pinned) while it is written.
    if (Status room = evictor_->MakeRoom(record.key, evictor_->EstimateBytes(record.key.n)); !room.ok()) {
      metrics_->sets_not_stored.fetch_add(1, std::memory_order_relaxed);
      spdlog::warn("cache write {}: {} (served, not stored)", name, room.message());
      return false;
    }
  }
  if (Status put = cache_->Put(record); !put.ok()) {
    // The set is still good: serve it, but say loudly that it was not kept.
    metrics_->sets_not_stored.fetch_add(1, std::memory_order_relaxed);
    spdlog::error("cache write {}: {} (served, not stored)", name, put.message());
    if (options_.on_write_error) options_.on_write_error(put);
    return false;
  }
  if (evictor_) evictor_->Touch(name, record.key);
  return true;
}

Scheduler::SliceEnd Scheduler::FillSlice(const std::shared_ptr<Job>& job) {
  const auto t0 = Clock::now();
  auto record = options_.fill(job->key);
  Status status;
  std::shared_ptr<const CanonicalEntry> entry;
  if (record.ok()) {
    metrics_->sets_filled.fetch_add(1, std::memory_order_relaxed);
    spdlog::info("filled {} from the writer in {:.3f} s (kept in memory)", job->name,
                 std::chrono::duration<double>(Clock::now() - t0).count());
    entry = std::make_shared<const CanonicalEntry>(std::move(record).value(), false);
    lru_.Put(job->name, entry);
  } else {
    spdlog::warn("fill {} from the writer: {}", job->name, record.status().message());
    status = record.status();
  }
  return Finish(job, status, std::move(entry));
}

Scheduler::SliceEnd Scheduler::ConstructedSlice(const std::shared_ptr<Job>& job, Construction construction) {
  const storage::SetKey& key = job->key;
  const char* name = ConstructionName(construction);
  // The canonical key's exact angles (30.25 on the quarter-degree grid); the
  // served set is this one aligned by swap / mirror: for a lattice the
  // lattice of the swapped / mirrored generator, for a centred net again a
  // centred net, each integrating the swapped / mirrored edges exactly as
  // well as the canonical set integrates its own; for a tent-folded lattice
  // the points aligned are again a folded lattice (the tent commutes with the
  // swap, and a mirror is a half shift before the fold), chosen for folded
  // edges that are their own mirror images.
  std::vector<double> dirs = {Phi1Degrees(key.dirs)};
  if (key.dirs.count == 2) dirs.push_back(Phi2Degrees(key.dirs));
  metrics_->optimizations_started.fetch_add(1, std::memory_order_relaxed);
  spdlog::info("{} start {}", name, job->name);
  const auto t0 = Clock::now();
  storage::SetRecord record;
  record.key = key;
  record.engine = name;
  std::string detail;
  // The seed is the realization number itself (server/construction.h).
  Status made;
  if (construction == Construction::kLattice || construction == Construction::kTentLattice) {
    const bool folded = construction == Construction::kTentLattice;
    AlignedLatticeOptions lattice;
    lattice.folded = folded;
    lattice.window_deg = folded ? kTentLatticeWindowDeg : kLatticeWindowDeg;
    lattice.threads = std::max(1, options_.threads_per_worker);
    lattice.cache = &lattice_terms_;
    auto choice = ChooseAlignedLatticeGenerator(key.n, dirs, lattice);
    made = choice.status();
    if (choice.ok()) {
      record.points = LatticePoints(key.n, choice->generator, key.realization, folded);
      detail = fmt::format("generator={} score={:.6g} candidates={}", choice->generator, choice->score,
                           choice->candidates);
    }
  } else {
    AlignedNetOptions net;
    net.window_deg = kNetWindowDeg;
    auto result = AlignedNet(key.n, dirs, key.realization, net);
    made = result.status();
    if (result.ok()) {
      record.points = std::move(result->points);
      record.iterations = result->sweeps;
      detail = fmt::format("objective {:.4g} -> {:.4g} flips={} sweeps={}", result->start_objective,
                           result->objective, result->flips, result->sweeps);
    }
  }
  Status status;
  std::shared_ptr<const CanonicalEntry> entry;
  if (!made.ok()) {
    metrics_->optimizations_failed.fetch_add(1, std::memory_order_relaxed);
    spdlog::error("{} failed {}: {}", name, job->name, made.message());
    status = Status::Internal(std::string(name) + " construction failed: " + made.message());
  } else {
    record.optimize_seconds = std::chrono::duration<double>(Clock::now() - t0).count();
    job->run_seconds += record.optimize_seconds;
    spdlog::info("{} done {} {} {:.3f} s", name, job->name, detail, record.optimize_seconds);
    entry = Complete(job->name, std::move(record));
  }
  return Finish(job, status, std::move(entry));
}

bool Scheduler::InFlight(const std::string& key_name) const {
  std::lock_guard<std::mutex> lock(mu_);
  return inflight_.count(key_name) != 0;
}

void Scheduler::BeginShutdown() {
  Callbacks callbacks;
  {
    std::lock_guard<std::mutex> lock(mu_);
    if (stopping_) return;
    stopping_ = true;
    std::vector<std::shared_ptr<Job>> queued;
    for (auto& [client, q] : clients_) {
      for (auto& w : q.waiting) {
        for (const auto& [seq, job] : w) queued.push_back(inflight_.at(job->name));
      }
    }
    for (const auto& job : queued) DequeueLocked(job.get());
    for (const auto& job : queued) {
      job->status = Status::Unavailable("the server is shutting down");
      FinishLocked(job, &callbacks);
    }
    if (!queued.empty()) spdlog::info("shutdown: dropped {} queued optimizations", queued.size());
    work_cv_.notify_all();
  }
  for (auto& fn : callbacks) fn();
}

void Scheduler::Shutdown() {
  BeginShutdown();
  for (auto& t : workers_) {
    if (t.joinable()) t.join();
  }
}

uint32_t Scheduler::queue_length() const {
  std::lock_guard<std::mutex> lock(mu_);
  return static_cast<uint32_t>(waiting_[0] + waiting_[1]);
}

uint32_t Scheduler::running() const {
  std::lock_guard<std::mutex> lock(mu_);
  return running_;
}

uint32_t Scheduler::paused() const {
  std::lock_guard<std::mutex> lock(mu_);
  return paused_;
}

}  // namespace alignset::server

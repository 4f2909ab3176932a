#include "server/scheduler.h"

#include <spdlog/spdlog.h>

#include <ctime>

#include "core/optimize/realization.h"

namespace alignset::server {

using Clock = std::chrono::steady_clock;

// Everything in a Job is guarded by Scheduler::mu_.
struct Job {
  storage::SetKey key;
  std::string name;  // KeyString(key), for the maps and the logs
  int priority = 0;
  uint64_t seq = 0;
  int waiters = 0;
  JobView::State state = JobView::State::kQueued;
  ProgressInfo progress;
  Clock::time_point started;
  uint64_t version = 0;
  // Set when the job was given up (no waiters left, or shutdown): it has
  // left `inflight_`, so a new request starts a new job.
  bool abandoned = false;
  std::condition_variable cv;
  Status status;
  std::shared_ptr<const CanonicalEntry> entry;
  bool from_cache = false;
};

// ---------------------------------------------------------------- Ticket

Ticket::~Ticket() {
  if (job_) scheduler_->Release(job_);
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
  if (job_->state == JobView::State::kQueued) {
    for (const auto& q : scheduler_->queue_) {
      if (std::get<2>(q) == job_.get()) break;
      ++v.queue_position;
    }
  } else {
    v.elapsed_seconds = std::chrono::duration<double>(Clock::now() - job_->started).count();
  }
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

// ------------------------------------------------------------- Scheduler

Scheduler::Scheduler(const Options& options, storage::SetCache* cache, Metrics* metrics)
    : options_(options), cache_(cache), metrics_(metrics), lru_(options.memory_cache_bytes) {}

StatusOr<std::unique_ptr<Scheduler>> Scheduler::Create(const Options& options,
                                                       storage::SetCache* cache, Metrics* metrics) {
  if (options.workers < 1) return Status::InvalidArgument("workers must be at least 1");
  if (options.max_queue < 1) return Status::InvalidArgument("max_queue must be at least 1");
  if (Status s = ValidateOptions(options.optimizer); !s.ok()) return s;
  std::unique_ptr<Scheduler> s(new Scheduler(options, cache, metrics));
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

std::string Scheduler::ProfileFor(uint32_t n) const {
  std::lock_guard<std::mutex> lock(profile_mu_);
  auto it = profiles_.find(n);
  if (it != profiles_.end()) return it->second;
  std::string p = storage::ProfileId(DefaultFrequencyParams(n), options_.optimizer, options_.seed);
  profiles_.emplace(n, p);
  return p;
}

storage::SetKey Scheduler::KeyFor(uint32_t n, const CanonicalDirections& dirs,
                                  uint32_t realization) const {
  return storage::SetKey{n, dirs, ProfileFor(n), realization};
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

StatusOr<std::unique_ptr<Ticket>> Scheduler::Acquire(const storage::SetKey& key, Priority priority) {
  const std::string name = KeyString(key);
  if (auto hit = lru_.Get(name)) {
    metrics_->cache_hits_memory.fetch_add(1, std::memory_order_relaxed);
    return Ready(std::move(hit));
  }
  const int prio = static_cast<int>(priority);
  // Joins the key's job if there is one; mu_ held.
  auto join = [&](const std::shared_ptr<Job>& job) {
    ++job->waiters;
    if (job->state == JobView::State::kQueued && prio < job->priority) {
      queue_.erase({job->priority, job->seq, job.get()});
      job->priority = prio;
      queue_.insert({job->priority, job->seq, job.get()});
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
    return Ready(std::move(entry));
  }
  if (stored.status().code() == Status::Code::kDataLoss) {
    metrics_->corrupt_rows.fetch_add(1, std::memory_order_relaxed);
    spdlog::warn("corrupt row {}: {}; recomputing", name, stored.status().message());
  } else if (stored.status().code() != Status::Code::kNotFound) {
    spdlog::error("cache read {}: {}", name, stored.status().message());
    return Status::Unavailable("cache read failed: " + stored.status().message());
  }

  std::lock_guard<std::mutex> lock(mu_);
  if (stopping_) return Status::Unavailable("the server is shutting down");
  // Another request may have started (or finished) the job meanwhile.
  if (auto it = inflight_.find(name); it != inflight_.end()) return join(it->second);
  if (auto hit = lru_.Get(name)) {
    metrics_->cache_hits_memory.fetch_add(1, std::memory_order_relaxed);
    return Ready(std::move(hit));
  }
  if (queue_.size() >= static_cast<size_t>(options_.max_queue)) {
    metrics_->rejected_queue_full.fetch_add(1, std::memory_order_relaxed);
    spdlog::warn("queue full ({} waiting), rejected {}", queue_.size(), name);
    return Status::ResourceExhausted("the optimization queue is full (" +
                                     std::to_string(queue_.size()) + " waiting); retry later");
  }
  auto job = std::make_shared<Job>();
  job->key = key;
  job->name = name;
  job->priority = prio;
  job->seq = next_seq_++;
  job->waiters = 1;
  inflight_.emplace(name, job);
  queue_.insert({job->priority, job->seq, job.get()});
  metrics_->cache_misses.fetch_add(1, std::memory_order_relaxed);
  spdlog::info("queued {} ({}, position {})", name,
               priority == Priority::kInteractive ? "interactive" : "batch", queue_.size() - 1);
  work_cv_.notify_one();
  return std::unique_ptr<Ticket>(new Ticket(this, job, nullptr));
}

void Scheduler::Release(const std::shared_ptr<Job>& job) {
  std::lock_guard<std::mutex> lock(mu_);
  if (--job->waiters > 0 || job->state != JobView::State::kQueued) return;
  // The last waiter left a job that has not started: drop it. A running job
  // notices at its next progress callback.
  queue_.erase({job->priority, job->seq, job.get()});
  job->abandoned = true;
  job->status = Status::Cancelled("every waiter left");
  metrics_->optimizations_cancelled.fetch_add(1, std::memory_order_relaxed);
  spdlog::info("withdrawn {} (no waiters left before it ran)", job->name);
  FinishLocked(job);
}

void Scheduler::FinishLocked(const std::shared_ptr<Job>& job) {
  job->state = JobView::State::kDone;
  ++job->version;
  if (auto it = inflight_.find(job->name); it != inflight_.end() && it->second == job) {
    inflight_.erase(it);
  }
  job->cv.notify_all();
}

void Scheduler::WorkerLoop(SpectralEngine* engine) {
  for (;;) {
    std::shared_ptr<Job> job;
    {
      std::unique_lock<std::mutex> lock(mu_);
      work_cv_.wait(lock, [&] { return stopping_ || !queue_.empty(); });
      if (stopping_) return;
      Job* next = std::get<2>(*queue_.begin());
      queue_.erase(queue_.begin());
      job = inflight_.at(next->name);
      job->state = JobView::State::kRunning;
      job->started = Clock::now();
      ++job->version;
      ++running_;
      job->cv.notify_all();
    }
    RunJob(job, engine);
    std::lock_guard<std::mutex> lock(mu_);
    --running_;
    FinishLocked(job);
  }
}

void Scheduler::RunJob(const std::shared_ptr<Job>& job, SpectralEngine* engine) {
  const storage::SetKey& key = job->key;
  // Another server process (or an earlier run) may have stored it by now.
  if (auto stored = cache_->Get(key); stored.ok()) {
    auto entry = std::make_shared<const CanonicalEntry>(std::move(stored).value());
    lru_.Put(job->name, entry);
    metrics_->cache_hits_db.fetch_add(1, std::memory_order_relaxed);
    std::lock_guard<std::mutex> lock(mu_);
    job->entry = std::move(entry);
    job->from_cache = true;
    return;
  }

  OptimizationProblem problem;
  problem.n = key.n;
  problem.directions = {Phi1Degrees(key.dirs)};
  if (key.dirs.count == 2) problem.directions.push_back(Phi2Degrees(key.dirs));
  problem.seed = RealizationSeed(options_.seed, key.realization);
  metrics_->optimizations_started.fetch_add(1, std::memory_order_relaxed);
  spdlog::info("optimize start {} engine={} max_iterations={}", job->name, engine->name(),
               EffectiveMaxIterations(options_.optimizer, key.n, key.dirs.count));
  const auto t0 = Clock::now();
  auto result = Optimize(problem, options_.optimizer, *engine, [&](const ProgressInfo& p) {
    std::lock_guard<std::mutex> lock(mu_);
    job->progress = p;
    ++job->version;
    job->cv.notify_all();
    if (job->waiters > 0 && !stopping_) return true;
    // Given up: leave inflight_ now so that a request arriving from here on
    // starts a new job instead of joining one that is stopping.
    job->abandoned = true;
    if (auto it = inflight_.find(job->name); it != inflight_.end() && it->second == job) {
      inflight_.erase(it);
    }
    return false;
  });
  const double seconds = std::chrono::duration<double>(Clock::now() - t0).count();

  Status status;
  std::shared_ptr<const CanonicalEntry> entry;
  bool abandoned, stopping;
  {
    std::lock_guard<std::mutex> lock(mu_);
    abandoned = job->abandoned;
    stopping = stopping_;
  }
  if (!result.ok()) {
    metrics_->optimizations_failed.fetch_add(1, std::memory_order_relaxed);
    spdlog::error("optimize failed {}: {}", job->name, result.status().message());
    status = Status::Internal("optimization failed: " + result.status().message());
  } else if (abandoned || result->stop_reason == StopReason::kCancelled) {
    metrics_->optimizations_cancelled.fetch_add(1, std::memory_order_relaxed);
    spdlog::info("optimize cancelled {} after {} iterations ({:.2f} s): {}", job->name,
                 result->iterations, seconds, stopping ? "shutdown" : "no waiters left");
    status = stopping ? Status::Unavailable("the server is shutting down")
                       : Status::Cancelled("every waiter left");
  } else {
    storage::SetRecord record;
    record.key = key;
    record.points = std::move(result->points);
    record.loss = result->final_loss;
    record.iterations = result->iterations;
    record.optimize_seconds = seconds;
    record.engine = engine->name();
    record.created_unix = static_cast<int64_t>(std::time(nullptr));
    if (Status put = cache_->Put(record); !put.ok()) {
      // The set is still good: serve it, but say loudly that it was not kept.
      spdlog::error("cache write {}: {} (served, not stored)", job->name, put.message());
    }
    metrics_->optimizations_completed.fetch_add(1, std::memory_order_relaxed);
    metrics_->RecordOptimization(seconds);
    spdlog::info("optimize done {} loss={:.6g} spectrum={:.6g} sw={:.6g} iterations={} {:.2f} s",
                 job->name, record.loss.total, record.loss.spectrum, record.loss.sw,
                 record.iterations, seconds);
    entry = std::make_shared<const CanonicalEntry>(std::move(record));
    lru_.Put(job->name, entry);
  }
  std::lock_guard<std::mutex> lock(mu_);
  job->status = status;
  job->entry = std::move(entry);
}

void Scheduler::BeginShutdown() {
  std::lock_guard<std::mutex> lock(mu_);
  if (stopping_) return;
  stopping_ = true;
  std::vector<std::shared_ptr<Job>> queued;
  for (const auto& q : queue_) queued.push_back(inflight_.at(std::get<2>(q)->name));
  queue_.clear();
  for (const auto& job : queued) {
    job->status = Status::Unavailable("the server is shutting down");
    FinishLocked(job);
  }
  if (!queued.empty()) spdlog::info("shutdown: dropped {} queued optimizations", queued.size());
  work_cv_.notify_all();
}

void Scheduler::Shutdown() {
  BeginShutdown();
  for (auto& t : workers_) {
    if (t.joinable()) t.join();
  }
}

uint32_t Scheduler::queue_length() const {
  std::lock_guard<std::mutex> lock(mu_);
  return static_cast<uint32_t>(queue_.size());
}

uint32_t Scheduler::running() const {
  std::lock_guard<std::mutex> lock(mu_);
  return running_;
}

}  // namespace alignset::server

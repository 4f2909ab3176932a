#include "server/scheduler.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <ctime>
#include <iterator>

#include "core/align/key_lineage.h"

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

Scheduler::Scheduler(const Options& options, Metrics* metrics) : options_(options), metrics_(metrics) {}

StatusOr<std::unique_ptr<Scheduler>> Scheduler::Create(const Options& options,
                                                       storage::SetCache* cache, Metrics* metrics) {
  if (options.workers < 1) return Status::InvalidArgument("workers must be at least 1");
  if (options.max_queue < 1) return Status::InvalidArgument("max_queue must be at least 1");
  if (options.max_queue_per_client < 1) return Status::InvalidArgument("max_queue_per_client must be at least 1");
  if (options.max_paused < 0) return Status::InvalidArgument("max_paused must be at least 0");
  if (options.time_slice.count() < 0) return Status::InvalidArgument("time_slice must be at least 0");
  if (Status s = ValidateOptions(options.producer.optimizer); !s.ok()) return s;
  Options o = options;
  // A progress callback every iteration: it is where a job yields its worker
  // (fairness) and notices that its waiters left. It costs one uncontended
  // lock per iteration and does not change the set (progress_every is not
  // part of the profile).
  o.producer.optimizer.progress_every = 1;
  if (o.producer.read_only) o.producer.max_cache_bytes = 0;
  std::unique_ptr<Scheduler> s(new Scheduler(o, metrics));
  SetProducer::Options po = o.producer;
  po.pinned = [p = s.get()](const std::string& name) { return p->InFlight(name); };
  auto producer = SetProducer::Create(po, cache, metrics);
  if (!producer.ok()) return producer.status();
  s->producer_ = std::move(producer).value();
  for (int i = 0; i < options.workers; ++i) {
    auto engine = options.engine_factory
                      ? options.engine_factory()
                      : MakeSpectralEngine(options.engine, options.producer.threads_per_worker);
    if (!engine.ok()) return engine.status();
    s->engines_.push_back(std::move(engine).value());
  }
  for (auto& engine : s->engines_) {
    s->workers_.emplace_back([p = s.get(), e = engine.get()] { p->WorkerLoop(e); });
  }
  return s;
}

// The producer goes first: its evictor asks InFlight() until it stops.
Scheduler::~Scheduler() {
  Shutdown();
  producer_.reset();
}

// ------------------------------------------------- the queue (mu_ held)

void Scheduler::EnqueueLocked(Job* job) {
  clients_[job->client].waiting[job->priority].insert({job->seq, job});
  ++waiting_[job->priority];
  if (job->paused) ++paused_;
  CountsChangedLocked();
}

void Scheduler::DequeueLocked(Job* job) {
  auto it = clients_.find(job->client);
  if (it == clients_.end() || it->second.waiting[job->priority].erase({job->seq, job}) == 0) return;
  --waiting_[job->priority];
  if (job->paused) --paused_;
  CountsChangedLocked();
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
  if (auto hit = producer_->FromMemory(name, key, /*touch=*/true)) return Ready(std::move(hit));
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
  auto stored = producer_->FromCache(name, key);
  if (stored.ok()) return Ready(std::move(stored).value());
  if (stored.status().code() == Status::Code::kDataLoss) {
    metrics_->corrupt_rows.fetch_add(1, std::memory_order_relaxed);
    spdlog::warn("corrupt row {}: {}; recomputing", name, stored.status().message());
  } else if (stored.status().code() != Status::Code::kNotFound) {
    spdlog::error("cache read {}: {}", name, stored.status().message());
    return Status::Unavailable("cache read failed: " + stored.status().message());
  }
  if (options_.producer.read_only && !options_.producer.fill) {
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
  if (auto hit = producer_->FromMemory(name, key, /*touch=*/false)) return Ready(std::move(hit));
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
      CountsChangedLocked();
      job->cv.notify_all();
    }
    const SliceEnd end = RunSlice(job, engine, engine_job == job->seq);
    engine_job = job->seq;
    Callbacks callbacks;
    {
      std::lock_guard<std::mutex> lock(mu_);
      --running_;
      CountsChangedLocked();
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
          spdlog::info("optimize cancelled {} as it paused: {}", job->name,
                       stopping_ ? "shutdown" : "no waiters left");
        }
        FinishLocked(job, &callbacks);
      }
    }
    for (auto& fn : callbacks) fn();
  }
}

Scheduler::SliceEnd Scheduler::RunSlice(const std::shared_ptr<Job>& job, SpectralEngine* engine,
                                        bool engine_holds_k) {
  if (job->run) {
    spdlog::debug("optimize resume {} at iteration {}", job->name, job->run->iteration());
    return OptimizeSlice(job, engine, engine_holds_k);
  }
  // Another server process (or an earlier run) may have stored it by now.
  if (auto stored = producer_->FromCache(job->name, job->key); stored.ok()) {
    std::lock_guard<std::mutex> lock(mu_);
    job->entry = std::move(stored).value();
    job->from_cache = true;
    return SliceEnd::kDone;
  }
  if (options_.producer.fill) {
    // The call to the writer is cancelled when every waiter has left (or
    // the server stops), as an optimization notices at its next slice.
    auto filled = producer_->Fill(job->name, job->key, [this, job] {
      std::lock_guard<std::mutex> lock(mu_);
      return job->waiters == 0 || stopping_;
    });
    if (!filled.ok() && filled.status().code() == Status::Code::kCancelled) {
      metrics_->optimizations_cancelled.fetch_add(1, std::memory_order_relaxed);
      spdlog::info("fill cancelled {}: {}", job->name, filled.status().message());
    }
    return Finish(job, filled.status(), filled.ok() ? std::move(filled).value() : nullptr);
  }
  if (!ConstructionOfProfile(job->key.profile).optimized()) {
    // Built in one slice (not paused, not stopped: seconds at most).
    double seconds = 0.0;
    auto built = producer_->Construct(job->name, job->key, &seconds);
    job->run_seconds += seconds;
    return Finish(job, built.status(), built.ok() ? std::move(built).value() : nullptr);
  }
  if (job->chain.empty()) {
    LineagePlan plan = producer_->PlanLineage(job->name, job->key);
    std::lock_guard<std::mutex> lock(mu_);
    job->chain = std::move(plan.chain);
    job->chain_next = 0;
    job->warm_start = std::move(plan.warm_start);
    job->chain_iterations_done = 0;
    job->chain_iterations_total = plan.iterations_total;
  }
  const storage::SetKey& target = job->chain[job->chain_next];
  std::optional<PointSet> start = std::move(job->warm_start);
  job->warm_start.reset();
  auto run = producer_->StartOptimization(job->name, target, std::move(start), engine->name());
  if (!run.ok()) return Finish(job, run.status(), nullptr);
  {
    std::lock_guard<std::mutex> lock(mu_);
    job->run = std::move(run).value();
  }
  return OptimizeSlice(job, engine, engine_holds_k);
}

Scheduler::SliceEnd Scheduler::OptimizeSlice(const std::shared_ptr<Job>& job, SpectralEngine* engine,
                                             bool engine_holds_k) {
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
    entry = producer_->Complete(target_name, std::move(record));
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

Scheduler::SliceEnd Scheduler::Finish(const std::shared_ptr<Job>& job, const Status& status,
                                      std::shared_ptr<const CanonicalEntry> entry) {
  std::lock_guard<std::mutex> lock(mu_);
  job->status = status;
  job->entry = std::move(entry);
  return SliceEnd::kDone;
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

void Scheduler::CountsChangedLocked() {
  if (counts_waiters_.empty()) return;
  const auto queued = static_cast<uint32_t>(waiting_[0] + waiting_[1]);
  for (CountsWaiter* w : counts_waiters_) {
    if (!w->met && (*w->until)(queued, running_, paused_)) w->met = true;
  }
  counts_cv_.notify_all();
}

bool Scheduler::WaitForCounts(const std::function<bool(uint32_t, uint32_t, uint32_t)>& until,
                              std::chrono::milliseconds timeout) const {
  std::unique_lock<std::mutex> lock(mu_);
  CountsWaiter w{&until};
  w.met = until(static_cast<uint32_t>(waiting_[0] + waiting_[1]), running_, paused_);
  counts_waiters_.push_back(&w);
  counts_cv_.wait_for(lock, timeout, [&] { return w.met; });
  counts_waiters_.erase(std::find(counts_waiters_.begin(), counts_waiters_.end(), &w));
  return w.met;
}

}  // namespace alignset::server

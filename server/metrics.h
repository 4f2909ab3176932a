#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <mutex>

#include "server/histogram.h"

namespace alignset::server {

struct MetricsSnapshot {
  uint64_t requests_get = 0;
  uint64_t requests_watch = 0;
  uint64_t requests_precompute = 0;
  uint64_t requests_samples = 0;
  uint64_t requests_estimate = 0;
  uint64_t requests_invalid = 0;
  uint64_t cache_hits_memory = 0;
  uint64_t cache_hits_db = 0;
  uint64_t cache_misses = 0;
  uint64_t corrupt_rows = 0;
  uint64_t optimizations_started = 0;
  uint64_t optimizations_completed = 0;
  uint64_t optimizations_cancelled = 0;
  uint64_t optimizations_failed = 0;
  uint64_t shared_waits = 0;
  uint64_t rejected_queue_full = 0;
  uint64_t requests_unauthenticated = 0;
  uint64_t sets_not_stored = 0;
  uint64_t rejected_client_limit = 0;
  uint64_t rejected_waiting_limit = 0;
  uint64_t optimizations_paused = 0;
  uint64_t database_integrity_errors = 0;
  uint32_t paused = 0;
  uint32_t queue_length = 0;
  uint32_t running = 0;
  double optimize_seconds_total = 0.0;
  double optimize_seconds_max = 0.0;
  double uptime_seconds = 0.0;
};

// Counters shared by the service and the scheduler. Lock-free on the hot
// path (cache hits); the optimization times take a mutex, once per set.
class Metrics {
 public:
  std::atomic<uint64_t> requests_get{0};
  std::atomic<uint64_t> requests_watch{0};
  std::atomic<uint64_t> requests_precompute{0};
  std::atomic<uint64_t> requests_samples{0};
  std::atomic<uint64_t> requests_estimate{0};
  std::atomic<uint64_t> requests_invalid{0};
  std::atomic<uint64_t> cache_hits_memory{0};
  std::atomic<uint64_t> cache_hits_db{0};
  std::atomic<uint64_t> cache_misses{0};
  std::atomic<uint64_t> corrupt_rows{0};
  std::atomic<uint64_t> optimizations_started{0};
  std::atomic<uint64_t> optimizations_completed{0};
  std::atomic<uint64_t> optimizations_cancelled{0};
  std::atomic<uint64_t> optimizations_failed{0};
  std::atomic<uint64_t> shared_waits{0};
  std::atomic<uint64_t> rejected_queue_full{0};
  // Calls refused for a missing or wrong bearer token; the request counters
  // above count authorized calls only.
  std::atomic<uint64_t> requests_unauthenticated{0};
  // Sets optimized and served but not written to SQLite (read-only or full
  // disk, damaged pages): each is recomputed after a restart.
  std::atomic<uint64_t> sets_not_stored{0};
  // New jobs refused because their client had --max-queue-per-client
  // waiting.
  std::atomic<uint64_t> rejected_client_limit{0};
  // Calls refused at --max-waiting-calls.
  std::atomic<uint64_t> rejected_waiting_limit{0};
  // Slices that ended with the job yielding its worker (fairness).
  std::atomic<uint64_t> optimizations_paused{0};
  // False when the start-up write probe failed (SetCache::ProbeWrite).
  std::atomic<bool> database_writable{true};
  // Database damage found by PRAGMA quick_check (at start, and after the
  // first failed write): the number of problems it listed, 0 when clean.
  std::atomic<uint64_t> database_integrity_errors{0};
  std::atomic<uint64_t> integrity_checks{0};
  // A read-only replica (--read-only): misses it refused (no --fill-from),
  // and sets it got from its writer (--fill-from), kept in memory only.
  std::atomic<bool> read_only{false};
  std::atomic<uint64_t> replica_misses{0};
  std::atomic<uint64_t> sets_filled{0};
  // A bounded file (--max-cache-bytes): sets evicted, their bytes (an
  // estimate: blob plus row overhead, whole pages), the file's size at the
  // last look, and background vacuum passes.
  int64_t max_cache_bytes = 0;
  std::atomic<uint64_t> cache_evictions{0};
  std::atomic<uint64_t> cache_evicted_bytes{0};
  std::atomic<int64_t> cache_file_bytes{0};
  std::atomic<uint64_t> cache_vacuums{0};

  // Latency of each call from its arrival to its end (set, error or
  // cancel), and of each optimization (its slices).
  Histogram latency_get{Histogram::LatencyBounds()};
  Histogram latency_watch{Histogram::LatencyBounds()};
  Histogram latency_precompute{Histogram::LatencyBounds()};
  Histogram latency_samples{Histogram::LatencyBounds()};
  Histogram optimization_seconds{Histogram::LatencyBounds()};

  void RecordOptimization(double seconds) {
    optimization_seconds.Observe(seconds);
    std::lock_guard<std::mutex> lock(mu_);
    optimize_seconds_total_ += seconds;
    if (seconds > optimize_seconds_max_) optimize_seconds_max_ = seconds;
  }

  // Queue figures come from the scheduler at snapshot time.
  MetricsSnapshot Snapshot(uint32_t queue_length, uint32_t running) const {
    MetricsSnapshot s;
    s.requests_get = requests_get.load();
    s.requests_watch = requests_watch.load();
    s.requests_precompute = requests_precompute.load();
    s.requests_samples = requests_samples.load();
    s.requests_estimate = requests_estimate.load();
    s.requests_invalid = requests_invalid.load();
    s.cache_hits_memory = cache_hits_memory.load();
    s.cache_hits_db = cache_hits_db.load();
    s.cache_misses = cache_misses.load();
    s.corrupt_rows = corrupt_rows.load();
    s.optimizations_started = optimizations_started.load();
    s.optimizations_completed = optimizations_completed.load();
    s.optimizations_cancelled = optimizations_cancelled.load();
    s.optimizations_failed = optimizations_failed.load();
    s.shared_waits = shared_waits.load();
    s.rejected_queue_full = rejected_queue_full.load();
    s.requests_unauthenticated = requests_unauthenticated.load();
    s.sets_not_stored = sets_not_stored.load();
    s.rejected_client_limit = rejected_client_limit.load();
    s.optimizations_paused = optimizations_paused.load();
    s.rejected_waiting_limit = rejected_waiting_limit.load();
    s.database_integrity_errors = database_integrity_errors.load();
    s.queue_length = queue_length;
    s.running = running;
    {
      std::lock_guard<std::mutex> lock(mu_);
      s.optimize_seconds_total = optimize_seconds_total_;
      s.optimize_seconds_max = optimize_seconds_max_;
    }
    s.uptime_seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    return s;
  }

 private:
  mutable std::mutex mu_;
  double optimize_seconds_total_ = 0.0;
  double optimize_seconds_max_ = 0.0;
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
};

}  // namespace alignset::server

// The short synchronous calls: GetSamples, EstimateDirection, and what the
// server reports about itself (GetMetrics, GetCacheStats, ListCachedSets).
#include "server/service.h"

#include <spdlog/spdlog.h>

#include <cmath>
#include <optional>

#include "server/direction_request.h"
#include "server/log_text.h"
#include "server/process_memory.h"
#include "server/samples.h"
#include "server/service_internal.h"
#include "server/validation.h"
#include "storage/sqlite_handle.h"

namespace alignset::server {
using service_internal::Clock;
using service_internal::Since;

grpc::Status AlignSetService::GetSamples(grpc::ServerContext* ctx, const v1::SamplesRequest* req,
                                         v1::SamplesResponse* resp) {
  struct Timed {
    Histogram* h;
    Clock::time_point t0 = Clock::now();
    ~Timed() { h->Observe(Since(t0)); }
  } timed{&metrics_->latency_samples};
  if (auto a = Authorize(ctx); !a.ok()) return a;
  metrics_->requests_samples.fetch_add(1, std::memory_order_relaxed);
  if (Status s = ValidatePointCount(req->n(), config_.max_n); !s.ok()) return Invalid(s, "GetSamples");
  std::optional<double> shear;
  if (req->has_shear_deg()) {
    if (!std::isfinite(req->shear_deg())) {
      return Invalid(Status::InvalidArgument("shear_deg is not a finite number"), "GetSamples");
    }
    shear = req->shear_deg();
  }
  spdlog::debug("GetSamples {} N={} seed={}", Quoted(req->sampler()), req->n(), req->seed());
  auto points = MakeBaselineSamples(req->sampler(), req->n(), req->seed(), shear);
  if (!points.ok()) {
    if (points.status().code() == Status::Code::kInvalidArgument) return Invalid(points.status(), "GetSamples");
    return ToGrpc(points.status());
  }
  resp->set_n(static_cast<uint32_t>(points->size()));
  resp->set_points(EncodePoints(*points));
  resp->set_sampler(req->sampler());
  resp->set_sheared(shear.has_value());
  resp->set_shear_deg(shear.value_or(0.0));
  return grpc::Status::OK;
}

grpc::Status AlignSetService::EstimateDirection(grpc::ServerContext* ctx,
                                                const v1::EstimateDirectionRequest* req,
                                                v1::EstimateDirectionResponse* resp) {
  metrics_->requests_estimate.fetch_add(1, std::memory_order_relaxed);
  if (auto a = Authorize(ctx); !a.ok()) return a;
  auto input = ParseDirectionRequest(*req);
  if (!input.ok()) return Invalid(input.status(), "EstimateDirection");
  auto estimate = RunDirectionEstimate(*input);
  if (!estimate.ok()) {
    if (estimate.status().code() == Status::Code::kInvalidArgument) {
      return Invalid(estimate.status(), "EstimateDirection");
    }
    return ToGrpc(estimate.status());
  }
  FillDirectionResponse(*estimate, resp);
  spdlog::debug("EstimateDirection: {} -> {}", input->is_grid ? "grid" : "samples",
                estimate->first.status == DirectionStatus::kFound
                    ? std::to_string(estimate->first.theta_deg)
                    : estimate->first.reason);
  return grpc::Status::OK;
}

void AlignSetService::FillMetrics(v1::MetricsResponse* out) const {
  const MetricsSnapshot s = metrics_->Snapshot(scheduler_->queue_length(), scheduler_->running());
  out->set_requests_get(s.requests_get);
  out->set_requests_watch(s.requests_watch);
  out->set_requests_precompute(s.requests_precompute);
  out->set_requests_samples(s.requests_samples);
  out->set_requests_estimate(s.requests_estimate);
  out->set_requests_invalid(s.requests_invalid);
  out->set_cache_hits_memory(s.cache_hits_memory);
  out->set_cache_hits_db(s.cache_hits_db);
  out->set_cache_misses(s.cache_misses);
  out->set_corrupt_rows(s.corrupt_rows);
  out->set_optimizations_started(s.optimizations_started);
  out->set_optimizations_completed(s.optimizations_completed);
  out->set_optimizations_cancelled(s.optimizations_cancelled);
  out->set_optimizations_failed(s.optimizations_failed);
  out->set_shared_waits(s.shared_waits);
  out->set_queue_length(s.queue_length);
  out->set_running(s.running);
  out->set_optimize_seconds_total(s.optimize_seconds_total);
  out->set_optimize_seconds_max(s.optimize_seconds_max);
  out->set_rejected_queue_full(s.rejected_queue_full);
  out->set_uptime_seconds(s.uptime_seconds);
  out->set_requests_unauthenticated(s.requests_unauthenticated);
  out->set_sets_not_stored(s.sets_not_stored);
  out->set_rejected_client_limit(s.rejected_client_limit);
  out->set_optimizations_paused(s.optimizations_paused);
  out->set_paused(scheduler_->paused());
  out->set_waiting_calls(static_cast<uint32_t>(waiting_calls_.load()));
  out->set_rejected_waiting_limit(s.rejected_waiting_limit);
  out->set_database_integrity_errors(s.database_integrity_errors);
  out->set_read_only(metrics_->read_only.load());
  out->set_replica_misses(metrics_->replica_misses.load());
  out->set_sets_filled(metrics_->sets_filled.load());
  out->set_max_cache_bytes(metrics_->max_cache_bytes);
  out->set_cache_evictions(metrics_->cache_evictions.load());
  out->set_cache_evicted_bytes(metrics_->cache_evicted_bytes.load());
  out->set_cache_file_bytes(metrics_->cache_file_bytes.load());
  out->set_cache_vacuums(metrics_->cache_vacuums.load());
  const ProcessMemory process = ReadProcessMemory();
  out->set_resident_bytes(process.resident_bytes);
  out->set_resident_anonymous_bytes(process.resident_anonymous_bytes);
  out->set_resident_file_bytes(process.resident_file_bytes);
  out->set_heap_allocated_bytes(process.heap_allocated_bytes);
  out->set_heap_free_bytes(process.heap_free_bytes);
  out->set_allocator(process.allocator);
  const SetProducer::MemoryUse caches = scheduler_->producer().memory();
  out->set_memory_cache_bytes(static_cast<int64_t>(caches.sets_bytes));
  out->set_memory_cache_capacity_bytes(static_cast<int64_t>(caches.sets_capacity));
  out->set_lattice_terms_bytes(static_cast<int64_t>(caches.lattice_bytes));
  out->set_lattice_terms_capacity_bytes(static_cast<int64_t>(caches.lattice_capacity));
  out->set_sqlite_memory_bytes(storage::SqliteMemoryUsed());
  out->set_sqlite_memory_peak_bytes(storage::SqliteMemoryPeak());
}

grpc::Status AlignSetService::GetCacheStats(grpc::ServerContext* ctx,
                                            const v1::CacheStatsRequest*,
                                            v1::CacheStatsResponse* resp) {
  if (auto a = Authorize(ctx); !a.ok()) return a;
  auto stats = cache_->Stats();
  if (!stats.ok()) return ToGrpc(stats.status());
  resp->set_damaged(stats->damaged);
  resp->set_sets(stats->sets);
  resp->set_bytes(stats->bytes);
  resp->set_one_direction_sets(stats->one_direction_sets);
  resp->set_two_direction_sets(stats->two_direction_sets);
  resp->set_database_path(db_path_);
  resp->set_profile_hint(scheduler_->producer().ProfileFor(4096));
  FillMetrics(resp->mutable_metrics());
  return grpc::Status::OK;
}

grpc::Status AlignSetService::ListCachedSets(grpc::ServerContext* ctx,
                                             const v1::ListCachedSetsRequest* req,
                                             v1::ListCachedSetsResponse* resp) {
  if (auto a = Authorize(ctx); !a.ok()) return a;
  std::optional<uint32_t> n;
  if (req->n() != 0) n = req->n();
  std::optional<std::string> profile;
  if (!req->profile().empty()) profile = req->profile();
  auto keys = cache_->List(n, profile);
  if (!keys.ok()) return ToGrpc(keys.status());
  resp->set_total(keys->size());
  for (const storage::SetKey& k : *keys) {
    if (req->limit() != 0 && resp->keys_size() >= static_cast<int>(req->limit())) break;
    FillKey(k, resp->add_keys());
  }
  return grpc::Status::OK;
}

grpc::Status AlignSetService::GetMetrics(grpc::ServerContext* ctx, const v1::MetricsRequest*,
                                         v1::MetricsResponse* resp) {
  if (auto a = Authorize(ctx); !a.ok()) return a;
  FillMetrics(resp);
  return grpc::Status::OK;
}
}  // namespace alignset::server

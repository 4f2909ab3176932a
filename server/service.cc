#include "server/service.h"

#include <spdlog/spdlog.h>

#include <chrono>
#include <cmath>
#include <deque>
#include <thread>

#include "core/optimize/realization.h"
#include "core/spectral/frequency_set.h"
#include "server/direction_request.h"
#include "server/samples.h"
#include "server/validation.h"

namespace alignset::server {
namespace {

using Clock = std::chrono::steady_clock;
constexpr auto kPoll = std::chrono::milliseconds(50);

double Since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

// Why a handler stopped waiting: the deadline passed or the client left.
grpc::Status ClientGone(grpc::ServerContext* ctx) {
  if (ctx->deadline() <= std::chrono::system_clock::now()) {
    return grpc::Status(grpc::StatusCode::DEADLINE_EXCEEDED,
                        "deadline exceeded while waiting for the optimization");
  }
  return grpc::Status(grpc::StatusCode::CANCELLED, "cancelled by the client");
}

// Waits until the ticket is done; a non-OK status when the client went away.
grpc::Status AwaitTicket(grpc::ServerContext* ctx, const Ticket& ticket) {
  while (!ticket.Wait(kPoll)) {
    if (ctx->IsCancelled()) return ClientGone(ctx);
  }
  return grpc::Status::OK;
}

bool ConstantTimeEquals(const std::string& a, const std::string& b) {
  if (a.size() != b.size()) return false;
  unsigned char diff = 0;
  for (size_t i = 0; i < a.size(); ++i) diff |= static_cast<unsigned char>(a[i] ^ b[i]);
  return diff == 0;
}

}  // namespace

grpc::Status ToGrpc(const Status& s) {
  using C = grpc::StatusCode;
  C code = C::UNKNOWN;
  switch (s.code()) {
    case Status::Code::kOk: return grpc::Status::OK;
    case Status::Code::kInvalidArgument: code = C::INVALID_ARGUMENT; break;
    case Status::Code::kNotFound: code = C::NOT_FOUND; break;
    case Status::Code::kResourceExhausted: code = C::RESOURCE_EXHAUSTED; break;
    case Status::Code::kDeadlineExceeded: code = C::DEADLINE_EXCEEDED; break;
    case Status::Code::kUnavailable: code = C::UNAVAILABLE; break;
    case Status::Code::kCancelled: code = C::CANCELLED; break;
    case Status::Code::kDataLoss: code = C::DATA_LOSS; break;
    case Status::Code::kInternal: code = C::INTERNAL; break;
  }
  return grpc::Status(code, s.message());
}

AlignSetService::AlignSetService(const ServerConfig& config, std::string db_path,
                                 std::string token, storage::SetCache* cache,
                                 Scheduler* scheduler, Metrics* metrics)
    : config_(config),
      db_path_(std::move(db_path)),
      token_(std::move(token)),
      cache_(cache),
      scheduler_(scheduler),
      metrics_(metrics) {}

grpc::Status AlignSetService::Authorize(grpc::ServerContext* ctx) const {
  if (token_.empty()) return grpc::Status::OK;
  const auto& md = ctx->client_metadata();
  auto it = md.find("authorization");
  if (it == md.end()) {
    spdlog::warn("unauthenticated call from {}: no authorization metadata", ctx->peer());
    return grpc::Status(grpc::StatusCode::UNAUTHENTICATED,
                        "this server requires 'authorization: Bearer <token>'");
  }
  const std::string value(it->second.data(), it->second.size());
  const std::string prefix = "Bearer ";
  if (value.rfind(prefix, 0) != 0 || !ConstantTimeEquals(value.substr(prefix.size()), token_)) {
    spdlog::warn("unauthenticated call from {}: wrong token", ctx->peer());
    return grpc::Status(grpc::StatusCode::UNAUTHENTICATED, "invalid bearer token");
  }
  return grpc::Status::OK;
}

grpc::Status AlignSetService::Invalid(const Status& s, const char* rpc) const {
  metrics_->requests_invalid.fetch_add(1, std::memory_order_relaxed);
  spdlog::info("{}: refused: {}", rpc, s.message());
  return ToGrpc(s);
}

void AlignSetService::FillKey(const storage::SetKey& key, v1::CanonicalKey* out,
                              AngleGrid grid) const {
  out->set_n(key.n);
  out->set_direction_count(static_cast<uint32_t>(key.dirs.count));
  out->set_phi1_deg(key.dirs.phi1);
  out->set_phi2_deg(key.dirs.count == 2 ? key.dirs.phi2 : key.dirs.phi1);
  out->set_phi1_exact_deg(Phi1Degrees(key.dirs));
  out->set_profile(key.profile);
  if (key.dirs.count == 2 || key.dirs.phi1_quarter != 0) {
    grid = key.dirs.count == 2 ? AngleGrid::kWholeDegree : AngleGrid::kQuarterDegree;
  }
  out->set_steps_per_degree(static_cast<uint32_t>(StepsPerDegree(grid)));
  if (auto index = CanonicalKeyIndex(key.dirs, grid); index.ok()) out->set_index(*index);
  out->set_text(KeyString(key));
  out->set_realization(key.realization);
}

StatusOr<Canonicalization> AlignSetService::Canonicalize(const v1::AlignedSetRequest& req) const {
  auto grid = ResolveAngleGrid(req.steps_per_degree(), config_.angle_grid);
  if (!grid.ok()) return grid.status();
  const std::vector<double> dirs(req.directions_deg().begin(), req.directions_deg().end());
  return ValidateAlignedSetRequest(req.n(), dirs, config_.max_n, *grid);
}

void AlignSetService::FillSet(const Canonicalization& canon, const storage::SetKey& key,
                              const CanonicalEntry& entry, bool from_cache,
                              v1::AlignedSetResponse* out) const {
  const storage::SetRecord& rec = entry.record();
  out->set_n(static_cast<uint32_t>(rec.points.size()));
  out->set_points(*entry.Encoded(canon.ops));
  v1::SetMetadata* md = out->mutable_metadata();
  for (double d : canon.requested_deg) md->add_requested_deg(d);
  for (int d : canon.served_deg) md->add_served_deg(d);
  for (double d : canon.served_exact_deg) md->add_served_exact_deg(d);
  FillKey(key, md->mutable_key(), canon.grid);
  md->set_swapped(canon.ops.swap);
  md->set_inverted(canon.ops.invert);
  md->set_inverted_y(canon.ops.invert_y);
  md->mutable_loss()->set_total(rec.loss.total);
  md->mutable_loss()->set_spectrum(rec.loss.spectrum);
  md->mutable_loss()->set_sliced_wasserstein(rec.loss.sw);
  const FrequencyParams fp = DefaultFrequencyParams(key.n);
  const OptimizerOptions& opt = scheduler_->options().optimizer;
  v1::OptimizationParameters* p = md->mutable_parameters();
  p->set_length(fp.length);
  p->set_width(fp.width);
  p->set_radius(fp.radius);
  p->set_max_iterations(EffectiveMaxIterations(opt, key.n, key.dirs.count));
  p->set_learning_rate(opt.learning_rate);
  p->set_sw_weight(EffectiveSwWeight(opt, key.n));
  p->set_seed(RealizationSeed(scheduler_->options().seed, key.realization));
  p->set_algorithm_version(storage::kAlgorithmVersion);
  md->set_from_cache(from_cache);
  md->set_optimize_seconds(rec.optimize_seconds);
  md->set_iterations(rec.iterations);
  md->set_engine(rec.engine);
}

grpc::Status AlignSetService::GetAlignedSet(grpc::ServerContext* ctx,
                                            const v1::AlignedSetRequest* req,
                                            v1::AlignedSetResponse* resp) {
  metrics_->requests_get.fetch_add(1, std::memory_order_relaxed);
  if (auto a = Authorize(ctx); !a.ok()) return a;
  auto canon = Canonicalize(*req);
  if (!canon.ok()) return Invalid(canon.status(), "GetAlignedSet");
  if (Status r = ValidateRealization(req->realization()); !r.ok()) return Invalid(r, "GetAlignedSet");
  const storage::SetKey key = scheduler_->KeyFor(req->n(), canon->key, req->realization());
  auto ticket = scheduler_->Acquire(key, Priority::kInteractive);
  if (!ticket.ok()) return ToGrpc(ticket.status());
  if (auto w = AwaitTicket(ctx, **ticket); !w.ok()) {
    spdlog::info("GetAlignedSet {}: client stopped waiting ({})", KeyString(key), w.error_message());
    return w;
  }
  auto entry = (*ticket)->Result();
  if (!entry.ok()) return ToGrpc(entry.status());
  const bool from_cache = (*ticket)->from_cache();
  FillSet(*canon, key, **entry, from_cache, resp);
  // Hits are the hot path: logged only at debug level.
  spdlog::debug("served {} as {} ({})", KeyString(key), ToString(canon->ops),
                from_cache ? "hit" : "optimized");
  return grpc::Status::OK;
}

grpc::Status AlignSetService::WatchAlignedSet(grpc::ServerContext* ctx,
                                              const v1::AlignedSetRequest* req,
                                              grpc::ServerWriter<v1::WatchEvent>* writer) {
  metrics_->requests_watch.fetch_add(1, std::memory_order_relaxed);
  if (auto a = Authorize(ctx); !a.ok()) return a;
  auto canon = Canonicalize(*req);
  if (!canon.ok()) return Invalid(canon.status(), "WatchAlignedSet");
  if (Status r = ValidateRealization(req->realization()); !r.ok()) return Invalid(r, "WatchAlignedSet");
  const storage::SetKey key = scheduler_->KeyFor(req->n(), canon->key, req->realization());
  auto ticket = scheduler_->Acquire(key, Priority::kInteractive);
  if (!ticket.ok()) return ToGrpc(ticket.status());
  const Ticket& t = **ticket;

  // Events at most every 100 ms (progress callbacks can be much faster);
  // a change of state or queue position always goes out.
  uint64_t version = ~uint64_t{0};
  JobView::State last_state = JobView::State::kDone;
  size_t last_position = SIZE_MAX;
  Clock::time_point last_progress{};
  for (;;) {
    JobView v = t.WaitForChange(version, std::chrono::milliseconds(100));
    if (v.state == JobView::State::kDone) break;
    if (ctx->IsCancelled()) return ClientGone(ctx);
    v1::WatchEvent ev;
    bool send = false;
    if (v.state == JobView::State::kQueued) {
      if (last_state != v.state || v.queue_position != last_position) {
        ev.mutable_queued()->set_position(static_cast<uint32_t>(v.queue_position));
        last_position = v.queue_position;
        send = true;
      }
    } else if (last_state != v.state || Clock::now() - last_progress >= std::chrono::milliseconds(100)) {
      v1::Progress* p = ev.mutable_progress();
      p->set_iteration(v.progress.iteration);
      p->set_max_iterations(v.progress.max_iterations);
      p->set_loss(v.progress.loss);
      p->set_learning_rate(v.progress.learning_rate);
      p->set_elapsed_seconds(v.elapsed_seconds);
      last_progress = Clock::now();
      send = v.version != version;
    }
    last_state = v.state;
    version = v.version;
    if (send && !writer->Write(ev)) return ClientGone(ctx);
  }
  auto entry = t.Result();
  if (!entry.ok()) return ToGrpc(entry.status());
  v1::WatchEvent ev;
  FillSet(*canon, key, **entry, t.from_cache(), ev.mutable_set());
  if (!writer->Write(ev)) return ClientGone(ctx);
  return grpc::Status::OK;
}

grpc::Status AlignSetService::Precompute(grpc::ServerContext* ctx,
                                         const v1::PrecomputeRequest* req,
                                         grpc::ServerWriter<v1::PrecomputeProgress>* writer) {
  metrics_->requests_precompute.fetch_add(1, std::memory_order_relaxed);
  if (auto a = Authorize(ctx); !a.ok()) return a;
  if (req->n().empty()) return Invalid(Status::InvalidArgument("give at least one n"), "Precompute");
  if (req->n().size() > 64) {
    return Invalid(Status::InvalidArgument("at most 64 values of n per request"), "Precompute");
  }
  for (uint32_t n : req->n()) {
    if (Status s = ValidatePointCount(n, config_.max_n); !s.ok()) return Invalid(s, "Precompute");
  }
  std::vector<CanonicalDirections> space;
  // 0 means whole degrees here: the 46-key space and its order stay what
  // they were for every existing client.
  auto grid = ResolveAngleGrid(req->steps_per_degree(), AngleGrid::kWholeDegree);
  if (!grid.ok()) return Invalid(grid.status(), "Precompute");
  switch (req->space()) {
    case v1::ONE_DIRECTION:
    case v1::TWO_DIRECTIONS: {
      if (!req->keys().empty()) {
        return Invalid(Status::InvalidArgument("explicit keys need space = EXPLICIT"), "Precompute");
      }
      const int count = req->space() == v1::ONE_DIRECTION ? 1 : 2;
      const AngleGrid g = count == 1 ? *grid : AngleGrid::kWholeDegree;
      for (size_t i = 0; i < CanonicalKeyCount(count, g); ++i) {
        space.push_back(CanonicalKeyAt(count, i, g));
      }
      break;
    }
    case v1::EXPLICIT: {
      if (req->keys().empty()) {
        return Invalid(Status::InvalidArgument("space = EXPLICIT needs at least one key"), "Precompute");
      }
      for (const auto& k : req->keys()) {
        std::vector<double> d(k.directions_deg().begin(), k.directions_deg().end());
        if (!k.exact_directions_deg().empty()) {
          d.assign(k.exact_directions_deg().begin(), k.exact_directions_deg().end());
        }
        auto canon = ValidateAlignedSetRequest(req->n(0), d, config_.max_n, *grid);
        if (!canon.ok()) return Invalid(canon.status(), "Precompute");
        space.push_back(canon->key);
      }
      break;
    }
    default:
      return Invalid(Status::InvalidArgument("space must be ONE_DIRECTION, TWO_DIRECTIONS or EXPLICIT"),
                     "Precompute");
  }
  const uint32_t shards = std::max<uint32_t>(1, req->shard_count());
  if (req->shard_index() >= shards) {
    return Invalid(Status::InvalidArgument("shard index " + std::to_string(req->shard_index()) +
                                           " is not below the shard count " + std::to_string(shards)),
                   "Precompute");
  }
  if (Status s = ValidateRealizationCount(req->realizations()); !s.ok()) return Invalid(s, "Precompute");
  const uint32_t realizations = std::max<uint32_t>(1, req->realizations());
  std::vector<storage::SetKey> items;
  size_t i = 0;
  for (uint32_t n : req->n()) {
    for (const auto& dirs : space) {
      for (uint32_t r = 0; r < realizations; ++r) {
        if (i++ % shards == req->shard_index()) items.push_back(scheduler_->KeyFor(n, dirs, r));
      }
    }
  }
  spdlog::info("precompute: {} items (shard {}/{}) from {}", items.size(), req->shard_index(),
               shards, ctx->peer());

  const auto t0 = Clock::now();
  v1::PrecomputeProgress p;
  p.set_total(items.size());
  Clock::time_point last_sent{};
  bool client_gone = false;
  // Sends the counts; cache skips are throttled, everything else goes out.
  auto send = [&](const storage::SetKey* key, const std::string& error, bool force) {
    const uint64_t resolved = p.done() + p.cached_already() + p.failed();
    p.set_remaining(items.size() - resolved);
    p.set_elapsed_seconds(Since(t0));
    p.set_estimated_seconds_left(
        p.done() > 0 ? p.elapsed_seconds() / static_cast<double>(p.done()) * p.remaining()
                     : (p.remaining() == 0 ? 0.0 : -1.0));
    if (key) FillKey(*key, p.mutable_last_key(), *grid);
    p.set_last_error(error);
    if (!force && Clock::now() - last_sent < std::chrono::milliseconds(100)) return;
    last_sent = Clock::now();
    if (!writer->Write(p)) client_gone = true;
  };

  struct Outstanding {
    storage::SetKey key;
    std::unique_ptr<Ticket> ticket;
  };
  std::deque<Outstanding> outstanding;
  // Enough concurrent items to keep every worker busy; the batch never fills
  // the queue, so interactive requests always find room.
  const size_t window = static_cast<size_t>(config_.workers);
  auto reap = [&] {
    for (auto it = outstanding.begin(); it != outstanding.end();) {
      if (!it->ticket->Done()) {
        ++it;
        continue;
      }
      auto r = it->ticket->Result();
      std::string error;
      if (r.ok()) {
        if (it->ticket->from_cache()) {
          p.set_cached_already(p.cached_already() + 1);
        } else {
          p.set_done(p.done() + 1);
        }
      } else {
        p.set_failed(p.failed() + 1);
        error = r.status().message();
      }
      send(&it->key, error, true);
      it = outstanding.erase(it);
    }
  };

  for (const storage::SetKey& key : items) {
    if (ctx->IsCancelled() || client_gone) return ClientGone(ctx);
    auto stored = scheduler_->IsStored(key);
    if (stored.ok() && *stored) {
      p.set_cached_already(p.cached_already() + 1);
      send(&key, "", false);
      continue;
    }
    for (;;) {
      reap();
      if (ctx->IsCancelled() || client_gone) return ClientGone(ctx);
      if (outstanding.size() >= window) {
        outstanding.front().ticket->Wait(kPoll);
        continue;
      }
      auto ticket = scheduler_->Acquire(key, Priority::kBatch);
      if (ticket.ok()) {
        outstanding.push_back({key, std::move(ticket).value()});
        break;
      }
      if (ticket.status().code() == Status::Code::kResourceExhausted) {
        // Interactive work filled the queue; wait for room.
        if (outstanding.empty()) {
          std::this_thread::sleep_for(std::chrono::milliseconds(100));
        } else {
          outstanding.front().ticket->Wait(kPoll);
        }
        continue;
      }
      if (ticket.status().code() == Status::Code::kUnavailable) return ToGrpc(ticket.status());
      p.set_failed(p.failed() + 1);
      send(&key, ticket.status().message(), true);
      break;
    }
  }
  while (!outstanding.empty()) {
    reap();
    if (outstanding.empty()) break;
    if (ctx->IsCancelled() || client_gone) return ClientGone(ctx);
    outstanding.front().ticket->Wait(kPoll);
  }
  send(nullptr, "", true);
  spdlog::info("precompute finished: {} optimized, {} cached already, {} failed in {:.1f} s",
               p.done(), p.cached_already(), p.failed(), Since(t0));
  return grpc::Status::OK;
}

grpc::Status AlignSetService::GetSamples(grpc::ServerContext* ctx, const v1::SamplesRequest* req,
                                         v1::SamplesResponse* resp) {
  metrics_->requests_samples.fetch_add(1, std::memory_order_relaxed);
  if (auto a = Authorize(ctx); !a.ok()) return a;
  if (Status s = ValidatePointCount(req->n(), config_.max_n); !s.ok()) return Invalid(s, "GetSamples");
  std::optional<double> shear;
  if (req->has_shear_deg()) {
    if (!std::isfinite(req->shear_deg())) {
      return Invalid(Status::InvalidArgument("shear_deg is not a finite number"), "GetSamples");
    }
    shear = req->shear_deg();
  }
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
}

grpc::Status AlignSetService::GetCacheStats(grpc::ServerContext* ctx,
                                            const v1::CacheStatsRequest*,
                                            v1::CacheStatsResponse* resp) {
  if (auto a = Authorize(ctx); !a.ok()) return a;
  auto stats = cache_->Stats();
  if (!stats.ok()) return ToGrpc(stats.status());
  resp->set_sets(stats->sets);
  resp->set_bytes(stats->bytes);
  resp->set_one_direction_sets(stats->one_direction_sets);
  resp->set_two_direction_sets(stats->two_direction_sets);
  resp->set_database_path(db_path_);
  resp->set_profile_hint(scheduler_->ProfileFor(4096));
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

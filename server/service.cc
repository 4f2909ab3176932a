#include "server/service.h"

#include <spdlog/spdlog.h>

#include <chrono>
#include <cmath>
#include <deque>
#include <thread>

#include "core/optimize/realization.h"
#include "core/spectral/frequency_set.h"
#include "server/direction_request.h"
#include "server/log_text.h"
#include "server/samples.h"
#include "server/validation.h"
#include "server/watch_pacer.h"

namespace alignset::server {
namespace {

using Clock = std::chrono::steady_clock;
constexpr auto kPoll = std::chrono::milliseconds(50);

double Since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

// Why a call stopped waiting: the deadline passed or the client left.
grpc::Status ClientGone(grpc::ServerContextBase* ctx) {
  if (ctx->deadline() <= std::chrono::system_clock::now()) {
    return grpc::Status(grpc::StatusCode::DEADLINE_EXCEEDED,
                        "deadline exceeded while waiting for the optimization");
  }
  return grpc::Status(grpc::StatusCode::CANCELLED, "cancelled by the client");
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
      metrics_(metrics),
      loop_(std::make_unique<EventLoop>(std::chrono::milliseconds(100), [this] { TickWatches(); })) {}

AlignSetService::~AlignSetService() { loop_->Stop(); }

bool AlignSetService::TakeWaitingSlot() {
  if (waiting_calls_.fetch_add(1) < config_.max_waiting_calls) return true;
  waiting_calls_.fetch_sub(1);
  const uint64_t n = metrics_->rejected_waiting_limit.fetch_add(1, std::memory_order_relaxed) + 1;
  if ((n & (n - 1)) == 0) {
    spdlog::warn("{} calls already waiting (--max-waiting-calls), refused one ({} so far)",
                 config_.max_waiting_calls, n);
  }
  return false;
}

grpc::Status AlignSetService::Authorize(grpc::ServerContextBase* ctx) const {
  if (token_.empty()) return grpc::Status::OK;
  const auto& md = ctx->client_metadata();
  auto it = md.find("authorization");
  const char* problem = nullptr;
  if (it == md.end()) {
    problem = "no authorization metadata";
  } else {
    const std::string value(it->second.data(), it->second.size());
    const std::string prefix = "Bearer ";
    if (value.rfind(prefix, 0) != 0 || !ConstantTimeEquals(value.substr(prefix.size()), token_)) {
      problem = "wrong token";
    }
  }
  if (problem == nullptr) return grpc::Status::OK;
  // Counted apart from the request counters (which count authorized calls
  // only); logged at the 1st, 2nd, 4th, 8th, ... so that a flood of them
  // cannot flood the log.
  const uint64_t count = metrics_->requests_unauthenticated.fetch_add(1, std::memory_order_relaxed) + 1;
  if ((count & (count - 1)) == 0) {
    spdlog::warn("unauthenticated call from {}: {} ({} so far)", Quoted(ctx->peer()), problem, count);
  }
  return grpc::Status(grpc::StatusCode::UNAUTHENTICATED,
                      it == md.end() ? "this server requires 'authorization: Bearer <token>'"
                                     : "invalid bearer token");
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
  md->set_not_stored(!entry.stored());
}

// A GetAlignedSet call waiting for its optimization. It holds no thread:
// the ticket's done callback posts Complete() to the event loop, and gRPC's
// OnCancel ends it early when the client leaves. Owned by itself from Start
// to OnDone; closures elsewhere hold weak pointers.
class GetCall final : public grpc::ServerUnaryReactor, public std::enable_shared_from_this<GetCall> {
 public:
  GetCall(AlignSetService* service, grpc::CallbackServerContext* ctx, v1::AlignedSetResponse* resp,
          Canonicalization canon, storage::SetKey key, std::unique_ptr<Ticket> ticket,
          Clock::time_point t0)
      : service_(service), ctx_(ctx), resp_(resp), canon_(std::move(canon)), key_(std::move(key)),
        ticket_(std::move(ticket)), t0_(t0) {}

  grpc::ServerUnaryReactor* Start() {
    self_ = shared_from_this();
    std::weak_ptr<GetCall> weak = self_;
    EventLoop* loop = service_->loop_.get();
    ticket_->OnDone([weak, loop] {
      loop->Post([weak] {
        if (auto call = weak.lock()) call->Complete();
      });
    });
    return this;
  }

  void OnCancel() override {
    if (!Claim()) return;
    grpc::Status s = ClientGone(ctx_);
    spdlog::info("GetAlignedSet {}: client stopped waiting ({})", KeyString(key_), s.error_message());
    End(s);
  }

  void OnDone() override {
    ticket_.reset();  // withdraws the waiter if the job is still on
    service_->ReturnWaitingSlot();
    self_.reset();
  }

 private:
  // The first of Complete and OnCancel to get here finishes the call.
  bool Claim() {
    std::lock_guard<std::mutex> lock(mu_);
    if (claimed_) return false;
    claimed_ = true;
    return true;
  }
  void Complete() {
    if (!Claim()) return;
    auto entry = ticket_->Result();
    if (!entry.ok()) return End(ToGrpc(entry.status()));
    service_->FillSet(canon_, key_, **entry, ticket_->from_cache(), resp_);
    End(grpc::Status::OK);
  }
  void End(const grpc::Status& s) {
    service_->metrics_->latency_get.Observe(Since(t0_));
    Finish(s);
  }

  AlignSetService* const service_;
  grpc::CallbackServerContext* const ctx_;
  v1::AlignedSetResponse* const resp_;
  const Canonicalization canon_;
  const storage::SetKey key_;
  std::unique_ptr<Ticket> ticket_;
  const Clock::time_point t0_;
  std::mutex mu_;
  bool claimed_ = false;
  std::shared_ptr<GetCall> self_;
};

grpc::ServerUnaryReactor* AlignSetService::GetAlignedSet(grpc::CallbackServerContext* ctx,
                                                         const v1::AlignedSetRequest* req,
                                                         v1::AlignedSetResponse* resp) {
  const auto t0 = Clock::now();
  auto finish = [&](const grpc::Status& s) {
    metrics_->latency_get.Observe(Since(t0));
    grpc::ServerUnaryReactor* r = ctx->DefaultReactor();
    r->Finish(s);
    return r;
  };
  if (auto a = Authorize(ctx); !a.ok()) return finish(a);
  metrics_->requests_get.fetch_add(1, std::memory_order_relaxed);
  auto canon = Canonicalize(*req);
  if (!canon.ok()) return finish(Invalid(canon.status(), "GetAlignedSet"));
  if (Status r = ValidateRealization(req->realization()); !r.ok()) {
    return finish(Invalid(r, "GetAlignedSet"));
  }
  const storage::SetKey key = scheduler_->KeyFor(req->n(), canon->key, req->realization());
  auto ticket = scheduler_->Acquire(key, Priority::kInteractive, ctx->peer());
  if (!ticket.ok()) return finish(ToGrpc(ticket.status()));
  if ((*ticket)->Done()) {
    auto entry = (*ticket)->Result();
    if (!entry.ok()) return finish(ToGrpc(entry.status()));
    const bool from_cache = (*ticket)->from_cache();
    FillSet(*canon, key, **entry, from_cache, resp);
    // Hits are the hot path: logged only at debug level.
    spdlog::debug("served {} as {} ({})", KeyString(key), ToString(canon->ops),
                  from_cache ? "hit" : "optimized");
    return finish(grpc::Status::OK);
  }
  if (!TakeWaitingSlot()) {
    return finish(grpc::Status(grpc::StatusCode::RESOURCE_EXHAUSTED,
                               "too many calls are waiting for optimizations (" +
                                   std::to_string(config_.max_waiting_calls) +
                                   ", --max-waiting-calls); retry later"));
  }
  auto call = std::make_shared<GetCall>(this, ctx, resp, std::move(canon).value(), key,
                                        std::move(ticket).value(), t0);
  return call->Start();
}

// A WatchAlignedSet stream. Holds no thread: the event loop calls Tick()
// every 100 ms (and at once when the job is done), and Tick writes what the
// pacer says is due, one message at a time.
class WatchCall final : public grpc::ServerWriteReactor<v1::WatchEvent>,
                        public std::enable_shared_from_this<WatchCall> {
 public:
  WatchCall(AlignSetService* service, grpc::CallbackServerContext* ctx, Canonicalization canon,
            storage::SetKey key, std::unique_ptr<Ticket> ticket, Clock::time_point t0)
      : service_(service), ctx_(ctx), canon_(std::move(canon)), key_(std::move(key)),
        ticket_(std::move(ticket)), t0_(t0) {}

  grpc::ServerWriteReactor<v1::WatchEvent>* Start() {
    self_ = shared_from_this();
    service_->AddWatch(self_);
    std::weak_ptr<WatchCall> weak = self_;
    EventLoop* loop = service_->loop_.get();
    auto tick = [weak] {
      if (auto call = weak.lock()) call->Tick();
    };
    ticket_->OnDone([loop, tick] { loop->Post(tick); });
    loop->Post(tick);  // the first event (queue position, or the set) at once
    return this;
  }

  // What is due now, if nothing is being written.
  void Tick() {
    std::lock_guard<std::mutex> lock(mu_);
    if (ended_ || writing_) return;
    const JobView v = ticket_->View();
    ev_.Clear();
    if (v.state == JobView::State::kDone) {
      auto entry = ticket_->Result();
      if (!entry.ok()) return EndLocked(ToGrpc(entry.status()));
      service_->FillSet(canon_, key_, **entry, ticket_->from_cache(), ev_.mutable_set());
      last_ = true;
    } else {
      switch (pacer_.Next(v, Clock::now())) {
        case WatchPacer::Send::kNothing: return;
        case WatchPacer::Send::kQueued:
          ev_.mutable_queued()->set_position(static_cast<uint32_t>(v.queue_position));
          break;
        case WatchPacer::Send::kProgress: {
          v1::Progress* p = ev_.mutable_progress();
          p->set_iteration(v.progress.iteration);
          p->set_max_iterations(v.progress.max_iterations);
          p->set_loss(v.progress.loss);
          p->set_learning_rate(v.progress.learning_rate);
          p->set_elapsed_seconds(v.elapsed_seconds);
          break;
        }
      }
    }
    writing_ = true;
    StartWrite(&ev_);
  }

  void OnWriteDone(bool ok) override {
    std::lock_guard<std::mutex> lock(mu_);
    writing_ = false;
    if (ended_) return;
    if (!ok) return EndLocked(ClientGone(ctx_));
    if (last_) return EndLocked(grpc::Status::OK);
  }

  void OnCancel() override {
    std::lock_guard<std::mutex> lock(mu_);
    cancelled_ = true;
    // With a write in flight, OnWriteDone(false) ends the stream.
    if (!writing_) EndLocked(ClientGone(ctx_));
  }

  void OnDone() override {
    service_->RemoveWatch(this);
    ticket_.reset();
    service_->ReturnWaitingSlot();
    self_.reset();
  }

 private:
  void EndLocked(const grpc::Status& s) {
    if (ended_) return;
    ended_ = true;
    service_->metrics_->latency_watch.Observe(Since(t0_));
    Finish(s);
  }

  AlignSetService* const service_;
  grpc::CallbackServerContext* const ctx_;
  const Canonicalization canon_;
  const storage::SetKey key_;
  std::unique_ptr<Ticket> ticket_;
  const Clock::time_point t0_;
  std::mutex mu_;
  WatchPacer pacer_;
  v1::WatchEvent ev_;  // the message in flight: valid until OnWriteDone
  bool writing_ = false;
  bool last_ = false;
  bool ended_ = false;
  bool cancelled_ = false;
  std::shared_ptr<WatchCall> self_;
};

void AlignSetService::AddWatch(const std::shared_ptr<WatchCall>& call) {
  std::lock_guard<std::mutex> lock(watches_mu_);
  watches_[call.get()] = call;
}

void AlignSetService::RemoveWatch(const WatchCall* call) {
  std::lock_guard<std::mutex> lock(watches_mu_);
  watches_.erase(call);
}

void AlignSetService::TickWatches() {
  std::vector<std::shared_ptr<WatchCall>> live;
  {
    std::lock_guard<std::mutex> lock(watches_mu_);
    live.reserve(watches_.size());
    for (const auto& [ptr, weak] : watches_) {
      if (auto call = weak.lock()) live.push_back(std::move(call));
    }
  }
  for (const auto& call : live) call->Tick();
}

grpc::ServerWriteReactor<v1::WatchEvent>* AlignSetService::WatchAlignedSet(
    grpc::CallbackServerContext* ctx, const v1::AlignedSetRequest* req) {
  const auto t0 = Clock::now();
  // Refusals before the stream starts: a reactor that only finishes.
  class Refusal final : public grpc::ServerWriteReactor<v1::WatchEvent> {
   public:
    explicit Refusal(const grpc::Status& s) { Finish(s); }
    void OnDone() override { delete this; }
  };
  auto refuse = [&](const grpc::Status& s) {
    metrics_->latency_watch.Observe(Since(t0));
    return new Refusal(s);
  };
  if (auto a = Authorize(ctx); !a.ok()) return refuse(a);
  metrics_->requests_watch.fetch_add(1, std::memory_order_relaxed);
  auto canon = Canonicalize(*req);
  if (!canon.ok()) return refuse(Invalid(canon.status(), "WatchAlignedSet"));
  if (Status r = ValidateRealization(req->realization()); !r.ok()) {
    return refuse(Invalid(r, "WatchAlignedSet"));
  }
  const storage::SetKey key = scheduler_->KeyFor(req->n(), canon->key, req->realization());
  auto ticket = scheduler_->Acquire(key, Priority::kInteractive, ctx->peer());
  if (!ticket.ok()) return refuse(ToGrpc(ticket.status()));
  if (!TakeWaitingSlot()) {
    return refuse(grpc::Status(grpc::StatusCode::RESOURCE_EXHAUSTED,
                               "too many calls are waiting for optimizations (" +
                                   std::to_string(config_.max_waiting_calls) +
                                   ", --max-waiting-calls); retry later"));
  }
  auto call = std::make_shared<WatchCall>(this, ctx, std::move(canon).value(), key,
                                          std::move(ticket).value(), t0);
  return call->Start();
}

grpc::Status AlignSetService::Precompute(grpc::ServerContext* ctx,
                                         const v1::PrecomputeRequest* req,
                                         grpc::ServerWriter<v1::PrecomputeProgress>* writer) {
  if (auto a = Authorize(ctx); !a.ok()) return a;
  metrics_->requests_precompute.fetch_add(1, std::memory_order_relaxed);
  // A precompute stream holds a thread for as long as it runs: their number
  // is capped instead.
  struct StreamSlot {
    std::atomic<int>* count;
    Metrics* metrics;
    Clock::time_point t0 = Clock::now();
    ~StreamSlot() {
      count->fetch_sub(1);
      metrics->latency_precompute.Observe(Since(t0));
    }
  } slot{&precompute_streams_, metrics_};
  if (precompute_streams_.fetch_add(1) >= config_.max_precompute_streams) {
    return grpc::Status(grpc::StatusCode::RESOURCE_EXHAUSTED,
                        std::to_string(config_.max_precompute_streams) +
                            " precompute streams are running (--max-precompute-streams); retry later");
  }
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
  const uint64_t realizations = std::max<uint32_t>(1, req->realizations());
  // The items are enumerated as they are reached, not listed up front: a
  // request may name 64 N x 4141 keys x 64 realizations. Item i (N outer,
  // then keys, realizations inner) belongs to this shard when
  // i mod shards == shard_index.
  const uint64_t space_size = space.size();
  const uint64_t per_n = space_size * realizations;
  const uint64_t all = static_cast<uint64_t>(req->n().size()) * per_n;
  const uint64_t total = req->shard_index() < all ? (all - req->shard_index() + shards - 1) / shards : 0;
  auto item = [&](uint64_t j) {
    const uint64_t i = req->shard_index() + j * shards;
    return scheduler_->KeyFor(req->n(static_cast<int>(i / per_n)), space[(i / realizations) % space_size],
                              static_cast<uint32_t>(i % realizations));
  };
  const std::string client = ctx->peer();
  spdlog::info("precompute: {} items (shard {}/{}) from {}", total, req->shard_index(), shards,
               Quoted(client));

  const auto t0 = Clock::now();
  v1::PrecomputeProgress p;
  p.set_total(total);
  Clock::time_point last_sent{};
  bool client_gone = false;
  // Sends the counts; cache skips are throttled, everything else goes out.
  auto send = [&](const storage::SetKey* key, const std::string& error, bool force) {
    const uint64_t resolved = p.done() + p.cached_already() + p.failed();
    p.set_remaining(total - resolved);
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
  // The total goes out at once, and something at least every two seconds
  // while an item runs (an optimization at N = 65536 takes a minute or more).
  constexpr auto kHeartbeat = std::chrono::seconds(2);
  auto heartbeat = [&] {
    if (Clock::now() - last_sent >= kHeartbeat) send(nullptr, "", true);
  };
  send(nullptr, "", true);

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

  for (uint64_t j = 0; j < total; ++j) {
    const storage::SetKey key = item(j);
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
        heartbeat();
        continue;
      }
      auto ticket = scheduler_->Acquire(key, Priority::kBatch, client);
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
        heartbeat();
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
    heartbeat();
  }
  send(nullptr, "", true);
  spdlog::info("precompute finished: {} optimized, {} cached already, {} failed in {:.1f} s",
               p.done(), p.cached_already(), p.failed(), Since(t0));
  return grpc::Status::OK;
}

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

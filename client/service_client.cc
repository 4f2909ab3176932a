#include "alignset/client.h"

#include <grpcpp/grpcpp.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <chrono>
#include <cstring>
#include <fstream>
#include <sstream>

#include "alignset/v1/alignset.grpc.pb.h"
#include "core/optimize/realization.h"
#include "grpc/health/v1/health.grpc.pb.h"

namespace alignset {
namespace {

static_assert(SetRequest::kMaxRealization == kMaxRealization,
              "the public header states the core's realization bound");
static_assert(std::endian::native == std::endian::little,
              "the wire format is little-endian float64; add a byte swap for this host");

const char* CodeName(grpc::StatusCode c) {
  switch (c) {
    case grpc::StatusCode::OK: return "OK";
    case grpc::StatusCode::CANCELLED: return "CANCELLED";
    case grpc::StatusCode::UNKNOWN: return "UNKNOWN";
    case grpc::StatusCode::INVALID_ARGUMENT: return "INVALID_ARGUMENT";
    case grpc::StatusCode::DEADLINE_EXCEEDED: return "DEADLINE_EXCEEDED";
    case grpc::StatusCode::NOT_FOUND: return "NOT_FOUND";
    case grpc::StatusCode::ALREADY_EXISTS: return "ALREADY_EXISTS";
    case grpc::StatusCode::PERMISSION_DENIED: return "PERMISSION_DENIED";
    case grpc::StatusCode::RESOURCE_EXHAUSTED: return "RESOURCE_EXHAUSTED";
    case grpc::StatusCode::FAILED_PRECONDITION: return "FAILED_PRECONDITION";
    case grpc::StatusCode::ABORTED: return "ABORTED";
    case grpc::StatusCode::OUT_OF_RANGE: return "OUT_OF_RANGE";
    case grpc::StatusCode::UNIMPLEMENTED: return "UNIMPLEMENTED";
    case grpc::StatusCode::INTERNAL: return "INTERNAL";
    case grpc::StatusCode::UNAVAILABLE: return "UNAVAILABLE";
    case grpc::StatusCode::DATA_LOSS: return "DATA_LOSS";
    case grpc::StatusCode::UNAUTHENTICATED: return "UNAUTHENTICATED";
    default: return "UNKNOWN";
  }
}

Status FromGrpc(const grpc::Status& s, const std::string& address) {
  if (s.ok()) return Status::Ok();
  std::string m = std::string(CodeName(s.error_code())) + ": " + s.error_message();
  if (s.error_code() == grpc::StatusCode::UNAVAILABLE) m += " (server " + address + ")";
  switch (s.error_code()) {
    case grpc::StatusCode::INVALID_ARGUMENT:
    case grpc::StatusCode::OUT_OF_RANGE:
    case grpc::StatusCode::UNAUTHENTICATED:
    case grpc::StatusCode::PERMISSION_DENIED:
    case grpc::StatusCode::FAILED_PRECONDITION: return Status::InvalidArgument(m);
    case grpc::StatusCode::NOT_FOUND: return Status::NotFound(m);
    case grpc::StatusCode::RESOURCE_EXHAUSTED: return Status::ResourceExhausted(m);
    case grpc::StatusCode::DEADLINE_EXCEEDED: return Status::DeadlineExceeded(m);
    case grpc::StatusCode::UNAVAILABLE: return Status::Unavailable(m);
    case grpc::StatusCode::CANCELLED:
    case grpc::StatusCode::ABORTED: return Status::Cancelled(m);
    case grpc::StatusCode::DATA_LOSS: return Status::DataLoss(m);
    default: return Status::Internal(m);
  }
}

SetInfo ToInfo(const v1::SetMetadata& md, uint32_t n) {
  SetInfo i;
  i.requested_deg.assign(md.requested_deg().begin(), md.requested_deg().end());
  i.served_deg.assign(md.served_deg().begin(), md.served_deg().end());
  i.served_exact_deg.assign(md.served_exact_deg().begin(), md.served_exact_deg().end());
  // A server from before the quarter-degree grid sends only whole degrees.
  if (i.served_exact_deg.empty()) i.served_exact_deg.assign(i.served_deg.begin(), i.served_deg.end());
  i.phi1_exact = md.key().phi1_exact_deg();
  if (i.phi1_exact == 0.0) i.phi1_exact = md.key().phi1_deg();
  i.steps_per_degree =
      md.key().steps_per_degree() == 0 ? 1 : static_cast<int>(md.key().steps_per_degree());
  i.n = n;
  i.direction_count = static_cast<int>(md.key().direction_count());
  i.phi1 = md.key().phi1_deg();
  i.phi2 = md.key().phi2_deg();
  i.profile = md.key().profile();
  i.key_index = md.key().index();
  i.key_text = md.key().text();
  i.swapped = md.swapped();
  i.inverted = md.inverted();
  i.inverted_y = md.inverted_y();
  i.loss_total = md.loss().total();
  i.loss_spectrum = md.loss().spectrum();
  i.loss_sw = md.loss().sliced_wasserstein();
  i.length = md.parameters().length();
  i.width = md.parameters().width();
  i.radius = md.parameters().radius();
  i.max_iterations = md.parameters().max_iterations();
  i.learning_rate = md.parameters().learning_rate();
  i.sw_weight = md.parameters().sw_weight();
  i.seed = md.parameters().seed();
  i.realization = md.key().realization();
  i.algorithm_version = md.parameters().algorithm_version();
  i.from_cache = md.from_cache();
  i.optimize_seconds = md.optimize_seconds();
  i.iterations = md.iterations();
  i.engine = md.engine();
  // A server from before constructions sends none: its sets are optimized.
  if (!md.construction().empty()) i.construction = md.construction();
  i.lattice_generator = md.lattice_generator();
  return i;
}

ServiceMetrics ToMetrics(const v1::MetricsResponse& r) {
  ServiceMetrics m;
  m.requests_get = r.requests_get();
  m.requests_watch = r.requests_watch();
  m.requests_precompute = r.requests_precompute();
  m.requests_samples = r.requests_samples();
  m.requests_estimate = r.requests_estimate();
  m.requests_invalid = r.requests_invalid();
  m.cache_hits_memory = r.cache_hits_memory();
  m.cache_hits_db = r.cache_hits_db();
  m.cache_misses = r.cache_misses();
  m.corrupt_rows = r.corrupt_rows();
  m.optimizations_started = r.optimizations_started();
  m.optimizations_completed = r.optimizations_completed();
  m.optimizations_cancelled = r.optimizations_cancelled();
  m.optimizations_failed = r.optimizations_failed();
  m.shared_waits = r.shared_waits();
  m.rejected_queue_full = r.rejected_queue_full();
  m.queue_length = r.queue_length();
  m.running = r.running();
  m.paused = r.paused();
  m.waiting_calls = r.waiting_calls();
  m.optimizations_paused = r.optimizations_paused();
  m.rejected_client_limit = r.rejected_client_limit();
  m.rejected_waiting_limit = r.rejected_waiting_limit();
  m.requests_unauthenticated = r.requests_unauthenticated();
  m.database_integrity_errors = r.database_integrity_errors();
  m.sets_not_stored = r.sets_not_stored();
  m.optimize_seconds_total = r.optimize_seconds_total();
  m.optimize_seconds_max = r.optimize_seconds_max();
  m.uptime_seconds = r.uptime_seconds();
  m.read_only = r.read_only();
  m.replica_misses = r.replica_misses();
  m.sets_filled = r.sets_filled();
  m.max_cache_bytes = r.max_cache_bytes();
  m.cache_file_bytes = r.cache_file_bytes();
  m.cache_evictions = r.cache_evictions();
  m.cache_evicted_bytes = r.cache_evicted_bytes();
  m.cache_vacuums = r.cache_vacuums();
  m.resident_bytes = r.resident_bytes();
  m.resident_anonymous_bytes = r.resident_anonymous_bytes();
  m.resident_file_bytes = r.resident_file_bytes();
  m.allocator = r.allocator();
  m.heap_allocated_bytes = r.heap_allocated_bytes();
  m.heap_free_bytes = r.heap_free_bytes();
  m.memory_cache_bytes = r.memory_cache_bytes();
  m.memory_cache_capacity_bytes = r.memory_cache_capacity_bytes();
  m.lattice_terms_bytes = r.lattice_terms_bytes();
  m.lattice_terms_capacity_bytes = r.lattice_terms_capacity_bytes();
  m.sqlite_memory_bytes = r.sqlite_memory_bytes();
  m.sqlite_memory_peak_bytes = r.sqlite_memory_peak_bytes();
  return m;
}

PrecomputeUpdate ToUpdate(const v1::PrecomputeProgress& p) {
  PrecomputeUpdate u;
  u.total = p.total();
  u.done = p.done();
  u.cached_already = p.cached_already();
  u.failed = p.failed();
  u.remaining = p.remaining();
  u.running_fraction = p.running_fraction();
  u.elapsed_seconds = p.elapsed_seconds();
  u.estimated_seconds_left = p.estimated_seconds_left();
  u.last_key = p.last_key().text();
  u.last_error = p.last_error();
  return u;
}

}  // namespace

StatusOr<PointSet> DecodePoints(const std::string& bytes, uint32_t expected_n) {
  if (bytes.size() != static_cast<size_t>(expected_n) * 16) {
    return Status::InvalidArgument("the server sent " + std::to_string(bytes.size()) +
                                   " bytes of points for n = " + std::to_string(expected_n) +
                                   " (expected 16 per point)");
  }
  PointSet pts(expected_n);
  if (expected_n > 0) std::memcpy(pts.data(), bytes.data(), bytes.size());
  for (const Point2& p : pts) {
    if (!(p.x >= 0.0 && p.x < 1.0 && p.y >= 0.0 && p.y < 1.0)) {
      return Status::InvalidArgument("the server sent a point outside [0, 1)^2");
    }
  }
  return pts;
}

namespace {

// The longest timeout a call takes, about 31 years: a deadline is a clock
// reading in integer nanoseconds, which a larger one would overflow (1e12 s
// is past the year 2262); whoever means "no deadline" says 0.
constexpr double kMaxTimeoutSeconds = 1e9;
constexpr char kTimeoutRange[] = "a finite number of seconds in [0, 1e9]";

bool ValidTimeout(double s) { return std::isfinite(s) && s >= 0 && s <= kMaxTimeoutSeconds; }

Status CheckCallOptions(const CallOptions& call) {
  if (call.timeout_seconds && !ValidTimeout(*call.timeout_seconds)) {
    return Status::InvalidArgument(std::string("call timeout must be ") + kTimeoutRange +
                                   " (0: none)");
  }
  return Status::Ok();
}

}  // namespace

constexpr char kRetryServiceConfig[] = R"({
  "methodConfig": [{
    "name": [{"service": "alignset.v1.AlignSet"}, {"service": "grpc.health.v1.Health"}],
    "retryPolicy": {
      "maxAttempts": 4,
      "initialBackoff": "0.1s",
      "maxBackoff": "1s",
      "backoffMultiplier": 2,
      "retryableStatusCodes": ["UNAVAILABLE"]
    }
  }]
})";

struct ServiceClient::Impl {
  ConnectOptions options;
  std::shared_ptr<grpc::Channel> channel;
  std::unique_ptr<v1::AlignSet::Stub> stub;
  std::unique_ptr<grpc::health::v1::Health::Stub> health;

  using Clock = std::chrono::system_clock;
  struct Deadlines {
    std::optional<Clock::time_point> call;  // none: the call may take as long as it takes
    Clock::time_point connect;              // how long to wait for a connection
  };
  // The call's deadline: its own, else (unary calls only) the connection's
  // default; the connection wait ends at the connect timeout or there.
  Deadlines DeadlinesFrom(Clock::time_point start, bool unary, const CallOptions& call) const {
    const double timeout = call.timeout_seconds ? *call.timeout_seconds
                           : unary              ? options.timeout_seconds
                                                : 0.0;
    Deadlines d;
    d.connect = start + Seconds(options.connect_timeout_seconds);
    if (timeout > 0) {
      d.call = start + Seconds(timeout);
      d.connect = std::min(d.connect, *d.call);
    }
    return d;
  }
  // s is in [0, kMaxTimeoutSeconds] (Connect and CheckCallOptions refuse
  // the rest): a larger one would overflow the clock's integer ticks.
  static Clock::duration Seconds(double s) {
    return std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(s));
  }
  void Prepare(grpc::ClientContext* ctx, const Deadlines& d) const {
    if (!options.token.empty()) ctx->AddMetadata("authorization", "Bearer " + options.token);
    if (d.call) ctx->set_deadline(*d.call);
  }
  // A streaming call: the token and the deadline, once connected (or once
  // the connection wait is over).
  void Prepare(grpc::ClientContext* ctx, const CallOptions& call) const {
    const Deadlines d = DeadlinesFrom(Clock::now(), false, call);
    Prepare(ctx, d);
    AwaitConnection(d.connect);
  }
  // A unary call; `rpc(ctx)` sends it once. gRPC puts a channel whose
  // connection attempt failed into reconnect backoff and fails the RPCs sent
  // meanwhile at once, its own retries with them: a server that restarted,
  // or whose accept backlog was full, was an error although it answered a
  // moment later. So a call first waits for the connection, and one that
  // failed because the connection did (UNAVAILABLE and the channel no longer
  // ready) goes out again once it is back, until the connect timeout. An
  // UNAVAILABLE the server itself sent (the channel still ready) is final.
  template <class Rpc>
  grpc::Status Unary(const CallOptions& call, Rpc&& rpc) const {
    if (Status bad = CheckCallOptions(call); !bad.ok()) {
      return grpc::Status(grpc::StatusCode::INVALID_ARGUMENT, bad.message());
    }
    const Deadlines d = DeadlinesFrom(Clock::now(), true, call);
    for (;;) {
      grpc::ClientContext ctx;
      Prepare(&ctx, d);
      AwaitConnection(d.connect);
      grpc::Status s = rpc(&ctx);
      if (s.error_code() != grpc::StatusCode::UNAVAILABLE || Clock::now() >= d.connect ||
          channel->GetState(/*try_to_connect=*/false) == GRPC_CHANNEL_READY ||
          !AwaitConnection(d.connect)) {
        return s;
      }
    }
  }
  // Waits until `by` for the channel to be connected; whether it is. Past
  // `by` the call goes out anyway, so that its failure is gRPC's own, with
  // the last connection error in it.
  bool AwaitConnection(Clock::time_point by) const {
    if (options.connect_timeout_seconds <= 0) return false;
    grpc_connectivity_state state = channel->GetState(/*try_to_connect=*/true);
    while (state != GRPC_CHANNEL_READY) {
      if (state == GRPC_CHANNEL_SHUTDOWN || !channel->WaitForStateChange(state, by)) return false;
      state = channel->GetState(/*try_to_connect=*/true);
    }
    return true;
  }
  Status Fail(const grpc::Status& s) const { return FromGrpc(s, options.address); }
  StatusOr<std::vector<BatchItem>> Batch(const v1::AlignedSetsRequest& req,
                                         const CallOptions& call) const;
};

ServiceClient::ServiceClient(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
ServiceClient::~ServiceClient() = default;

StatusOr<std::unique_ptr<ServiceClient>> ServiceClient::Connect(const ConnectOptions& options) {
  if (options.address.empty()) return Status::InvalidArgument("empty server address");
  if (!ValidTimeout(options.connect_timeout_seconds)) {
    return Status::InvalidArgument(std::string("connect timeout must be ") + kTimeoutRange);
  }
  if (!ValidTimeout(options.timeout_seconds)) {
    return Status::InvalidArgument(std::string("timeout must be ") + kTimeoutRange + " (0: none)");
  }
  std::shared_ptr<grpc::ChannelCredentials> creds = grpc::InsecureChannelCredentials();
  if (!options.tls_ca_file.empty()) {
    std::ifstream in(options.tls_ca_file, std::ios::binary);
    if (!in) return Status::InvalidArgument("cannot read --tls-ca " + options.tls_ca_file);
    std::ostringstream pem;
    pem << in.rdbuf();
    grpc::SslCredentialsOptions ssl;
    ssl.pem_root_certs = pem.str();
    creds = grpc::SslCredentials(ssl);
  }
  grpc::ChannelArguments args;
  args.SetMaxReceiveMessageSize(-1);
  if (!options.tls_server_name.empty()) args.SetSslTargetNameOverride(options.tls_server_name);
  if (options.separate_connection) args.SetInt(GRPC_ARG_USE_LOCAL_SUBCHANNEL_POOL, 1);
  // A connection attempt can fail transiently (a loaded server's accept
  // backlog, a connection reset while it starts): retry UNAVAILABLE a few
  // times with backoff. Every AlignSet call is safe to repeat (a fetch, or a
  // computation the server de-duplicates), and the bound keeps a server that
  // is really down a quick, clear error (about 0.7 s).
  args.SetServiceConfigJSON(kRetryServiceConfig);
  // Reconnect soon after a failed attempt (gRPC's default waits a second
  // first), so a call waiting for the connection sees the server as soon as
  // it listens again.
  args.SetInt(GRPC_ARG_INITIAL_RECONNECT_BACKOFF_MS, 100);
  args.SetInt(GRPC_ARG_MIN_RECONNECT_BACKOFF_MS, 100);
  args.SetInt(GRPC_ARG_MAX_RECONNECT_BACKOFF_MS, 1000);
  auto impl = std::make_unique<Impl>();
  impl->options = options;
  impl->channel = grpc::CreateCustomChannel(options.address, creds, args);
  impl->stub = v1::AlignSet::NewStub(impl->channel);
  impl->health = grpc::health::v1::Health::NewStub(impl->channel);
  return std::unique_ptr<ServiceClient>(new ServiceClient(std::move(impl)));
}

namespace {
v1::AlignedSetRequest MakeRequest(const SetRequest& r) {
  v1::AlignedSetRequest req;
  req.set_n(r.n);
  for (double d : r.directions_deg) req.add_directions_deg(d);
  req.set_realization(r.realization);
  req.set_steps_per_degree(r.steps_per_degree);
  req.set_construction(r.construction);
  return req;
}

// A server that does not know constructions ignores the field and serves an
// optimized set: refuse that answer rather than pass it off as a lattice.
Status CheckConstruction(const std::string& construction, const SetInfo& info,
                         const std::string& address) {
  const std::string asked = construction.empty() ? "optimized" : construction;
  if (info.construction == asked) return Status::Ok();
  return FromGrpc(grpc::Status(grpc::StatusCode::FAILED_PRECONDITION,
                               "asked for construction '" + asked + "', the server answered '" +
                                   info.construction +
                                   "' (a server without constructions: update it)"),
                  address);
}

// The same for one item of a batch: a wrong answer becomes that item's error.
void CheckConstruction(const std::string& construction, BatchItem* item, const std::string& address) {
  if (!item->status.ok()) return;
  item->status = CheckConstruction(construction, item->set.info, address);
  if (!item->status.ok()) item->set = AlignedSet{};
}

EstimatedDirection ToDirection(const v1::EstimatedDirection& d) {
  EstimatedDirection e;
  e.found = d.status() == v1::DIRECTION_FOUND;
  e.theta_deg = d.theta_deg();
  e.kappa = d.kappa();
  e.confidence = d.confidence();
  e.contrast = d.contrast();
  e.reason = d.reason();
  return e;
}

StatusOr<AlignedSet> FromResponse(v1::AlignedSetResponse* resp) {
  AlignedSet out;
  auto pts = DecodePoints(resp->points(), resp->n());
  if (!pts.ok()) return pts.status();
  out.points = std::move(pts).value();
  out.info = ToInfo(resp->metadata(), resp->n());
  out.raw = std::move(*resp->mutable_points());
  return out;
}
}  // namespace

StatusOr<AlignedSet> ServiceClient::GetAlignedSet(uint32_t n, const std::vector<double>& dirs,
                                                  const CallOptions& call) {
  return GetAlignedSet(SetRequest{n, dirs, 0}, call);
}

StatusOr<AlignedSet> ServiceClient::GetAlignedSet(const SetRequest& request,
                                                  const CallOptions& call) {
  v1::AlignedSetResponse resp;
  grpc::Status s = impl_->Unary(call, [&](grpc::ClientContext* ctx) {
    return impl_->stub->GetAlignedSet(ctx, MakeRequest(request), &resp);
  });
  if (!s.ok()) return impl_->Fail(s);
  auto set = FromResponse(&resp);
  if (set.ok()) {
    if (Status c = CheckConstruction(request.construction, set->info, impl_->options.address); !c.ok()) {
      return c;
    }
  }
  return set;
}

namespace {
// The status of one batch item, in the same form as a failed call's.
Status ItemStatus(const v1::AlignedSetsItem& item, const std::string& address) {
  return FromGrpc(grpc::Status(static_cast<grpc::StatusCode>(item.code()), item.message()), address);
}
}  // namespace

StatusOr<std::vector<BatchItem>> ServiceClient::Impl::Batch(const v1::AlignedSetsRequest& req,
                                                            const CallOptions& call) const {
  v1::AlignedSetsResponse resp;
  grpc::Status s = Unary(call, [&](grpc::ClientContext* ctx) {
    return stub->GetAlignedSets(ctx, req, &resp);
  });
  if (!s.ok()) return Fail(s);
  std::vector<BatchItem> out(static_cast<size_t>(resp.items_size()));
  for (int i = 0; i < resp.items_size(); ++i) {
    v1::AlignedSetsItem* item = resp.mutable_items(i);
    if (item->code() != 0) {
      out[i].status = ItemStatus(*item, options.address);
      continue;
    }
    auto set = FromResponse(item->mutable_set());
    if (!set.ok()) {
      out[i].status = set.status();
      continue;
    }
    out[i].set = std::move(set).value();
  }
  return out;
}

StatusOr<std::vector<BatchItem>> ServiceClient::GetAlignedSets(const std::vector<SetRequest>& items,
                                                               const CallOptions& call) {
  v1::AlignedSetsRequest req;
  for (const SetRequest& r : items) *req.add_items() = MakeRequest(r);
  auto out = impl_->Batch(req, call);
  if (out.ok() && out->size() != items.size()) {
    return Status::Internal("the server answered " + std::to_string(out->size()) + " items for " +
                            std::to_string(items.size()));
  }
  if (out.ok()) {
    for (size_t i = 0; i < items.size(); ++i) {
      CheckConstruction(items[i].construction, &(*out)[i], impl_->options.address);
    }
  }
  return out;
}

StatusOr<std::vector<BatchItem>> ServiceClient::GetOneDirectionSpace(uint32_t n,
                                                                     uint32_t realization,
                                                                     const CallOptions& call) {
  return GetOneDirectionSpace(n, realization, "", call);
}

StatusOr<std::vector<BatchItem>> ServiceClient::GetOneDirectionSpace(uint32_t n,
                                                                     uint32_t realization,
                                                                     const std::string& construction,
                                                                     const CallOptions& call) {
  v1::AlignedSetsRequest req;
  req.set_space(v1::ONE_DIRECTION);
  req.set_space_n(n);
  req.set_space_realization(realization);
  req.set_space_construction(construction);
  auto out = impl_->Batch(req, call);
  if (out.ok()) {
    for (BatchItem& item : *out) CheckConstruction(construction, &item, impl_->options.address);
  }
  return out;
}

StatusOr<AlignedSet> ServiceClient::WatchAlignedSet(
    uint32_t n, const std::vector<double>& dirs,
    const std::function<void(const WatchUpdate&)>& on_update, const CallOptions& call) {
  return WatchAlignedSet(SetRequest{n, dirs, 0}, on_update, call);
}

StatusOr<AlignedSet> ServiceClient::WatchAlignedSet(
    const SetRequest& request, const std::function<void(const WatchUpdate&)>& on_update,
    const CallOptions& call) {
  if (Status bad = CheckCallOptions(call); !bad.ok()) return bad;
  grpc::ClientContext ctx;
  impl_->Prepare(&ctx, call);
  auto reader = impl_->stub->WatchAlignedSet(&ctx, MakeRequest(request));
  v1::WatchEvent ev;
  std::optional<StatusOr<AlignedSet>> result;
  while (reader->Read(&ev)) {
    if (ev.has_set()) {
      result = FromResponse(ev.mutable_set());
      continue;
    }
    WatchUpdate u;
    if (ev.has_queued()) {
      u.queued = true;
      u.queue_position = ev.queued().position();
    } else if (ev.has_progress()) {
      u.iteration = ev.progress().iteration();
      u.max_iterations = ev.progress().max_iterations();
      u.loss = ev.progress().loss();
      u.learning_rate = ev.progress().learning_rate();
      u.elapsed_seconds = ev.progress().elapsed_seconds();
    } else {
      continue;
    }
    if (on_update) on_update(u);
  }
  grpc::Status s = reader->Finish();
  if (!s.ok()) return impl_->Fail(s);
  if (!result) return Status::Internal("the server ended the stream without a set");
  if (result->ok()) {
    if (Status c = CheckConstruction(request.construction, (*result)->info, impl_->options.address);
        !c.ok()) {
      return c;
    }
  }
  return std::move(*result);
}

StatusOr<PrecomputeUpdate> ServiceClient::Precompute(
    const PrecomputeSpec& spec, const std::function<void(const PrecomputeUpdate&)>& on_update,
    const CallOptions& call) {
  if (Status bad = CheckCallOptions(call); !bad.ok()) return bad;
  v1::PrecomputeRequest req;
  for (uint32_t n : spec.n) req.add_n(n);
  switch (spec.space) {
    case 1: req.set_space(v1::ONE_DIRECTION); break;
    case 2: req.set_space(v1::TWO_DIRECTIONS); break;
    case 0:
      req.set_space(v1::EXPLICIT);
      for (const auto& k : spec.keys) {
        auto* e = req.add_keys();
        for (int d : k) e->add_directions_deg(d);
      }
      break;
    default: return Status::InvalidArgument("space must be 1, 2 or 0 (explicit keys)");
  }
  req.set_shard_index(spec.shard_index);
  req.set_shard_count(spec.shard_count);
  req.set_realizations(spec.realizations);
  req.set_steps_per_degree(spec.steps_per_degree);
  req.set_construction(spec.construction);
  grpc::ClientContext ctx;
  impl_->Prepare(&ctx, call);
  auto reader = impl_->stub->Precompute(&ctx, req);
  v1::PrecomputeProgress p;
  PrecomputeUpdate last;
  while (reader->Read(&p)) {
    last = ToUpdate(p);
    if (on_update) on_update(last);
  }
  grpc::Status s = reader->Finish();
  if (!s.ok()) return impl_->Fail(s);
  return last;
}

StatusOr<PointSet> ServiceClient::GetSamples(const std::string& sampler, uint32_t n, uint64_t seed,
                                             std::optional<double> shear_deg,
                                             const CallOptions& call) {
  v1::SamplesRequest req;
  req.set_sampler(sampler);
  req.set_n(n);
  req.set_seed(seed);
  if (shear_deg) req.set_shear_deg(*shear_deg);
  v1::SamplesResponse resp;
  grpc::Status s = impl_->Unary(call, [&](grpc::ClientContext* ctx) {
    return impl_->stub->GetSamples(ctx, req, &resp);
  });
  if (!s.ok()) return impl_->Fail(s);
  return DecodePoints(resp.points(), resp.n());
}

StatusOr<CacheInfo> ServiceClient::GetCacheStats(const CallOptions& call) {
  v1::CacheStatsResponse resp;
  grpc::Status s = impl_->Unary(call, [&](grpc::ClientContext* ctx) {
    return impl_->stub->GetCacheStats(ctx, v1::CacheStatsRequest(), &resp);
  });
  if (!s.ok()) return impl_->Fail(s);
  CacheInfo c;
  c.sets = resp.sets();
  c.bytes = resp.bytes();
  c.one_direction_sets = resp.one_direction_sets();
  c.two_direction_sets = resp.two_direction_sets();
  c.damaged = resp.damaged();
  c.database_path = resp.database_path();
  c.profile_hint = resp.profile_hint();
  c.metrics = ToMetrics(resp.metrics());
  return c;
}

StatusOr<ServiceMetrics> ServiceClient::GetMetrics(const CallOptions& call) {
  v1::MetricsResponse resp;
  grpc::Status s = impl_->Unary(call, [&](grpc::ClientContext* ctx) {
    return impl_->stub->GetMetrics(ctx, v1::MetricsRequest(), &resp);
  });
  if (!s.ok()) return impl_->Fail(s);
  return ToMetrics(resp);
}

StatusOr<std::vector<CachedKey>> ServiceClient::ListCachedSets(uint32_t n, const std::string& profile,
                                                               uint32_t limit,
                                                               const CallOptions& call) {
  v1::ListCachedSetsRequest req;
  req.set_n(n);
  req.set_profile(profile);
  req.set_limit(limit);
  v1::ListCachedSetsResponse resp;
  grpc::Status s = impl_->Unary(call, [&](grpc::ClientContext* ctx) {
    return impl_->stub->ListCachedSets(ctx, req, &resp);
  });
  if (!s.ok()) return impl_->Fail(s);
  std::vector<CachedKey> out;
  for (const auto& k : resp.keys()) {
    out.push_back({k.n(), static_cast<int>(k.direction_count()), k.phi1_deg(), k.phi2_deg(),
                   k.profile(), k.text()});
  }
  return out;
}

namespace {

StatusOr<DirectionReply> CallEstimate(ServiceClient::Impl* impl, const CallOptions& call,
                                      const v1::EstimateDirectionRequest& req) {
  v1::EstimateDirectionResponse resp;
  grpc::Status s = impl->Unary(call, [&](grpc::ClientContext* ctx) {
    return impl->stub->EstimateDirection(ctx, req, &resp);
  });
  if (!s.ok()) return impl->Fail(s);
  DirectionReply r;
  r.first = ToDirection(resp.first());
  r.has_second = resp.has_second();
  if (r.has_second) r.second = ToDirection(resp.second());
  r.max_radius = resp.max_radius();
  return r;
}

}  // namespace

StatusOr<DirectionReply> ServiceClient::EstimateDirection(int width, int height,
                                                          const std::vector<double>& values,
                                                          bool second, const CallOptions& call) {
  if (width < 0 || height < 0) return Status::InvalidArgument("negative grid size");
  v1::EstimateDirectionRequest req;
  req.mutable_grid()->set_width(static_cast<uint32_t>(width));
  req.mutable_grid()->set_height(static_cast<uint32_t>(height));
  req.mutable_grid()->mutable_values()->Add(values.begin(), values.end());
  req.set_second(second);
  return CallEstimate(impl_.get(), call, req);
}

StatusOr<DirectionReply> ServiceClient::EstimateDirection(const PointSet& points,
                                                          const std::vector<double>& values,
                                                          bool second, const CallOptions& call) {
  v1::EstimateDirectionRequest req;
  v1::ScatteredSamples* s = req.mutable_samples();
  for (const Point2& p : points) {
    s->add_x(p.x);
    s->add_y(p.y);
  }
  s->mutable_f()->Add(values.begin(), values.end());
  req.set_second(second);
  return CallEstimate(impl_.get(), call, req);
}

StatusOr<bool> ServiceClient::Healthy(const CallOptions& call) {
  grpc::health::v1::HealthCheckRequest req;
  grpc::health::v1::HealthCheckResponse resp;
  grpc::Status s = impl_->Unary(call, [&](grpc::ClientContext* ctx) {
    return impl_->health->Check(ctx, req, &resp);
  });
  if (!s.ok()) return impl_->Fail(s);
  return resp.status() == grpc::health::v1::HealthCheckResponse::SERVING;
}

}  // namespace alignset

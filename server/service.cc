// AlignSetService: construction, authorization and the helpers every call
// uses (status mapping, request canonicalization, filling a response).
// The calls themselves: service_get.cc, service_watch.cc,
// service_precompute.cc, service_batch.cc, service_info.cc.
#include "server/service.h"

#include <spdlog/spdlog.h>

#include "core/optimize/aligned_lattice.h"
#include "core/optimize/realization.h"
#include "core/spectral/frequency_set.h"
#include "server/bearer_token.h"
#include "server/construction.h"
#include "server/log_text.h"
#include "server/validation.h"

namespace alignset::server {

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
    case Status::Code::kFailedPrecondition: code = C::FAILED_PRECONDITION; break;
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
    if (!BearerTokenMatches(std::string_view(it->second.data(), it->second.size()), token_)) {
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

StatusOr<storage::SetKey> AlignSetService::KeyOf(const v1::AlignedSetRequest& req,
                                                 const Canonicalization& canon) const {
  if (Status r = ValidateRealization(req.realization()); !r.ok()) return r;
  auto construction = ParseConstruction(req.construction());
  if (!construction.ok()) return construction.status();
  if (Status s = (*construction)->ValidateSize(req.n()); !s.ok()) return s;
  return scheduler_->producer().KeyFor(req.n(), canon.key, req.realization(), (*construction)->kind);
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
  md->set_from_cache(from_cache);
  md->set_optimize_seconds(rec.optimize_seconds);
  md->set_iterations(rec.iterations);
  md->set_engine(rec.engine);
  md->set_not_stored(!entry.stored());
  const Construction& construction = ConstructionOfProfile(key.profile);
  md->set_construction(std::string(construction.name));
  if (!construction.optimized()) {
    // No optimization parameters: a lattice's or a net's seed is its
    // realization.
    v1::OptimizationParameters* p = md->mutable_parameters();
    p->set_seed(key.realization);
    p->set_algorithm_version(construction.version);
    if (construction.lattice()) {
      // The served set's generator: the canonical one carried by the same
      // swap / mirror as the points (MapLatticeGenerator).
      const auto g = entry.LatticeGenerator(key.realization, construction.folded());
      if (g) {
        md->set_lattice_generator(
            MapLatticeGenerator(key.n, *g, canon.ops.swap, canon.ops.invert, canon.ops.invert_y));
      }
    }
    return;
  }
  const FrequencyParams fp = DefaultFrequencyParams(key.n);
  const OptimizerOptions& opt = scheduler_->options().producer.optimizer;
  v1::OptimizationParameters* p = md->mutable_parameters();
  p->set_length(fp.length);
  p->set_width(fp.width);
  p->set_radius(fp.radius);
  p->set_max_iterations(EffectiveMaxIterations(opt, key.n, key.dirs.count));
  p->set_learning_rate(opt.learning_rate);
  p->set_sw_weight(EffectiveSwWeight(opt, key.n));
  p->set_seed(RealizationSeed(scheduler_->options().producer.seed, key.realization));
  p->set_algorithm_version(storage::kAlgorithmVersion);
}
}  // namespace alignset::server

#include "server/set_producer.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <ctime>

#include "core/align/key_lineage.h"
#include "core/optimize/realization.h"
#include "storage/profile.h"

namespace alignset::server {

using Clock = std::chrono::steady_clock;

SetProducer::SetProducer(const Options& options, storage::SetCache* cache, Metrics* metrics)
    : options_(options),
      cache_(cache),
      metrics_(metrics),
      lru_(options.memory_cache_bytes),
      lattice_terms_(options.lattice_terms_bytes) {}

StatusOr<std::unique_ptr<SetProducer>> SetProducer::Create(const Options& options, storage::SetCache* cache,
                                                           Metrics* metrics) {
  std::unique_ptr<SetProducer> p(new SetProducer(options, cache, metrics));
  if (options.max_cache_bytes > 0) {
    metrics->max_cache_bytes = options.max_cache_bytes;
    CacheEvictor::Options eo;
    eo.max_bytes = options.max_cache_bytes;
    eo.pinned = options.pinned;
    eo.order_file = options.eviction_order_file;
    eo.evicted = [lru = &p->lru_](const std::string& name) { lru->Erase(name); };
    p->evictor_ = std::make_unique<CacheEvictor>(cache, metrics, std::move(eo));
    if (Status st = p->evictor_->Start(); !st.ok()) return st;
  }
  return p;
}

std::string SetProducer::ProfileFor(uint32_t n, ConstructionKind construction) const {
  if (const Construction& c = ConstructionOf(construction); !c.optimized()) return std::string(c.profile);
  std::lock_guard<std::mutex> lock(profile_mu_);
  auto it = profiles_.find(n);
  if (it != profiles_.end()) return it->second;
  std::string p = storage::KeyProfile(n, ConstructionOf(construction), options_.optimizer, options_.seed);
  profiles_.emplace(n, p);
  return p;
}

storage::SetKey SetProducer::KeyFor(uint32_t n, const CanonicalDirections& dirs, uint32_t realization,
                                    ConstructionKind construction) const {
  return storage::SetKey{n, dirs, ProfileFor(n, construction), realization};
}

SetProducer::MemoryUse SetProducer::memory() const {
  MemoryUse m;
  m.sets_bytes = lru_.bytes();
  m.sets_capacity = lru_.capacity();
  m.lattice_bytes = lattice_terms_.stats().bytes;
  m.lattice_capacity = lattice_terms_.max_bytes();
  return m;
}

std::shared_ptr<const CanonicalEntry> SetProducer::FromMemory(const std::string& name,
                                                              const storage::SetKey& key, bool touch) {
  auto hit = lru_.Get(name);
  if (!hit) return nullptr;
  metrics_->cache_hits_memory.fetch_add(1, std::memory_order_relaxed);
  if (touch && evictor_) evictor_->Touch(name, key);
  return hit;
}

StatusOr<std::shared_ptr<const CanonicalEntry>> SetProducer::FromCache(const std::string& name,
                                                                       const storage::SetKey& key) {
  auto stored = cache_->Get(key);
  if (!stored.ok()) return stored.status();
  auto entry = std::make_shared<const CanonicalEntry>(std::move(stored).value());
  lru_.Put(name, entry);
  metrics_->cache_hits_db.fetch_add(1, std::memory_order_relaxed);
  if (evictor_) evictor_->Touch(name, key);
  return std::shared_ptr<const CanonicalEntry>(std::move(entry));
}

StatusOr<bool> SetProducer::IsStored(const storage::SetKey& key) {
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

StatusOr<std::shared_ptr<const CanonicalEntry>> SetProducer::Construct(const std::string& name,
                                                                       const storage::SetKey& key,
                                                                       double* seconds) {
  const Construction& construction = ConstructionOfProfile(key.profile);
  const std::string what(construction.name);
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
  spdlog::info("{} start {}", what, name);
  const auto t0 = Clock::now();
  ConstructionContext context;
  context.threads = std::max(1, options_.threads_per_worker);
  context.lattice_terms = &lattice_terms_;
  // The seed is the realization number itself (core/optimize/construction.h).
  auto made = construction.Build(key.n, dirs, key.realization, context);
  if (!made.ok()) {
    metrics_->optimizations_failed.fetch_add(1, std::memory_order_relaxed);
    spdlog::error("{} failed {}: {}", what, name, made.status().message());
    return Status::Internal(what + " construction failed: " + made.status().message());
  }
  storage::SetRecord record;
  record.key = key;
  record.engine = what;
  record.points = std::move(made->points);
  record.iterations = made->iterations;
  record.optimize_seconds = std::chrono::duration<double>(Clock::now() - t0).count();
  *seconds = record.optimize_seconds;
  spdlog::info("{} done {} {} {:.3f} s", what, name, made->detail, record.optimize_seconds);
  return Complete(name, std::move(record));
}

StatusOr<std::shared_ptr<const CanonicalEntry>> SetProducer::Fill(const std::string& name,
                                                                  const storage::SetKey& key,
                                                                  const std::function<bool()>& cancelled) {
  const auto t0 = Clock::now();
  auto record = options_.fill(key, cancelled);
  if (!record.ok()) {
    spdlog::warn("fill {} from the writer: {}", name, record.status().message());
    return record.status();
  }
  metrics_->sets_filled.fetch_add(1, std::memory_order_relaxed);
  spdlog::info("filled {} from the writer in {:.3f} s (kept in memory)", name,
               std::chrono::duration<double>(Clock::now() - t0).count());
  auto entry = std::make_shared<const CanonicalEntry>(std::move(record).value(), false);
  lru_.Put(name, entry);
  return std::shared_ptr<const CanonicalEntry>(std::move(entry));
}

std::optional<storage::SetKey> SetProducer::LineageParentKey(const storage::SetKey& key) const {
  if (!ConstructionOfProfile(key.profile).optimized() || !UsesKeyLineage(options_.optimizer, key.n)) {
    return std::nullopt;
  }
  const auto parent = WarmParent(key.dirs);
  if (!parent) return std::nullopt;
  storage::SetKey parent_key = key;
  parent_key.dirs = parent->parent;
  return parent_key;
}

LineagePlan SetProducer::PlanLineage(const std::string& name, const storage::SetKey& key) {
  LineagePlan plan;
  plan.chain = {key};
  // Up to a root (optimized from Owen-Sobol) or a stored ancestor.
  while (const auto parent_key = LineageParentKey(plan.chain.back())) {
    if (auto points = HeldSet(*parent_key)) {
      plan.warm_start = Align(*points, WarmParent(plan.chain.back().dirs)->ops);
      break;
    }
    plan.chain.push_back(*parent_key);
  }
  std::reverse(plan.chain.begin(), plan.chain.end());
  for (size_t i = 0; i < plan.chain.size(); ++i) {
    const storage::SetKey& k = plan.chain[i];
    const bool warm = i > 0 || plan.warm_start.has_value();
    const OptimizerOptions o = warm ? WarmStartOptions(options_.optimizer, k.n, k.dirs.count) : options_.optimizer;
    plan.iterations_total += EffectiveMaxIterations(o, k.n, k.dirs.count);
  }
  if (plan.chain.size() > 1) {
    spdlog::info("lineage {}: {} key(s) to optimize first, from {}", name, plan.chain.size() - 1,
                 plan.warm_start ? "a stored parent" : "a root");
  }
  return plan;
}

StatusOr<std::unique_ptr<OptimizerRun>> SetProducer::StartOptimization(const std::string& name,
                                                                       const storage::SetKey& target,
                                                                       std::optional<PointSet> warm_start,
                                                                       const std::string& engine_name) {
  OptimizationProblem problem;
  problem.n = target.n;
  problem.directions = {Phi1Degrees(target.dirs)};
  if (target.dirs.count == 2) problem.directions.push_back(Phi2Degrees(target.dirs));
  problem.seed = RealizationSeed(options_.seed, target.realization);
  OptimizerOptions options = options_.optimizer;
  if (warm_start) {
    problem.start = std::move(*warm_start);
    options = WarmStartOptions(options_.optimizer, target.n, target.dirs.count);
  }
  auto run = OptimizerRun::Create(problem, options);
  if (!run.ok()) {
    metrics_->optimizations_failed.fetch_add(1, std::memory_order_relaxed);
    spdlog::error("optimize failed {}: {}", name, run.status().message());
    return Status::Internal("optimization failed: " + run.status().message());
  }
  metrics_->optimizations_started.fetch_add(1, std::memory_order_relaxed);
  spdlog::info("optimize start {} engine={} max_iterations={}{}", KeyString(target), engine_name,
               EffectiveMaxIterations(options, target.n, target.dirs.count),
               problem.start ? " (warm: from its parent)" : "");
  return run;
}

std::optional<PointSet> SetProducer::HeldSet(const storage::SetKey& key) {
  const std::string name = KeyString(key);
  if (auto hit = lru_.Get(name)) return hit->record().points;
  if (auto stored = cache_->Get(key); stored.ok()) return std::move(stored->points);
  return std::nullopt;
}

std::shared_ptr<const CanonicalEntry> SetProducer::Complete(const std::string& name, storage::SetRecord record) {
  record.created_unix = static_cast<int64_t>(std::time(nullptr));
  const bool stored = Store(record, name);
  metrics_->optimizations_completed.fetch_add(1, std::memory_order_relaxed);
  metrics_->RecordOptimization(record.optimize_seconds);
  auto entry = std::make_shared<const CanonicalEntry>(std::move(record), stored);
  lru_.Put(name, entry);
  return entry;
}

bool SetProducer::Store(const storage::SetRecord& record, const std::string& name) {
  if (options_.read_only) {
    metrics_->sets_not_stored.fetch_add(1, std::memory_order_relaxed);
    return false;
  }
  if (evictor_) {
    // The key is still in flight (pinned) while it is written.
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

}  // namespace alignset::server

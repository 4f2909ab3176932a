// Precompute: a batch stream over a key space (lazily enumerated, at most
// one item per worker queued), with progress, heartbeats and an ETA.
#include "server/service.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <deque>
#include <memory>
#include <numeric>
#include <optional>
#include <string>
#include <thread>
#include <unordered_set>

#include "core/align/key_lineage.h"
#include "server/construction.h"
#include "server/log_text.h"
#include "server/service_internal.h"
#include "server/validation.h"

namespace alignset::server {
using service_internal::Clock;
using service_internal::ClientGone;
using service_internal::kPoll;
using service_internal::Since;

grpc::Status AlignSetService::Precompute(grpc::ServerContext* ctx,
                                         const v1::PrecomputeRequest* req,
                                         grpc::ServerWriter<v1::PrecomputeProgress>* writer) {
  if (auto a = Authorize(ctx); !a.ok()) return a;
  metrics_->requests_precompute.fetch_add(1, std::memory_order_relaxed);
  if (config_.read_only) {
    // Precompute exists to fill the file, which a replica never writes.
    return grpc::Status(grpc::StatusCode::FAILED_PRECONDITION,
                        "this server is a read-only replica (--read-only) of " + db_path_ +
                            ": precompute on the writer and ship its merged file");
  }
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
  auto construction = ParseConstruction(req->construction());
  if (!construction.ok()) return Invalid(construction.status(), "Precompute");
  for (uint32_t n : req->n()) {
    if (Status s = (*construction)->ValidateSize(n); !s.ok()) return Invalid(s, "Precompute");
  }
  const uint64_t realizations = std::max<uint32_t>(1, req->realizations());
  // The items are enumerated as they are reached, not listed up front: a
  // request may name 64 N x 4141 keys x 64 realizations. Work order: N
  // outer, then keys, realizations inner. Lattices take the keys in the
  // given order and item i belongs to shard i mod shards. Optimized keys are
  // taken in lineage order (core/align/key_lineage.h: grouped by root, each
  // group by depth, so every key comes after its parent) and a shard holds
  // one contiguous block of that order: a shard then finds almost every
  // key's parent stored by itself instead of recomputing ancestors that
  // other shards own, and a whole-space run optimizes each key once.
  const uint64_t space_size = space.size();
  const uint64_t per_n = space_size * realizations;
  const uint64_t all = static_cast<uint64_t>(req->n().size()) * per_n;
  const bool by_lineage = (*construction)->optimized();
  std::vector<uint64_t> order(space_size);
  std::iota(order.begin(), order.end(), uint64_t{0});
  uint64_t first = req->shard_index(), step = shards;
  uint64_t total = req->shard_index() < all ? (all - req->shard_index() + shards - 1) / shards : 0;
  if (by_lineage) {
    std::vector<std::pair<size_t, int>> rank(space_size);  // (root's index, depth)
    for (uint64_t k = 0; k < space_size; ++k) {
      // Roots are whole-degree keys on either grid.
      const auto root = CanonicalKeyIndex(LineageRoot(space[k]));
      rank[k] = {root.ok() ? *root : size_t{0}, LineageDepth(space[k])};
    }
    std::stable_sort(order.begin(), order.end(), [&](uint64_t a, uint64_t b) { return rank[a] < rank[b]; });
    first = all * req->shard_index() / shards;
    total = all * (req->shard_index() + 1) / shards - first;
    step = 1;
  }
  auto n_of = [&](uint64_t j) { return req->n(static_cast<int>((first + j * step) / per_n)); };
  auto item = [&](uint64_t j) {
    const uint64_t c = first + j * step;
    return scheduler_->producer().KeyFor(n_of(j),
                              space[order[(c / realizations) % space_size]],
                              static_cast<uint32_t>(c % realizations), (*construction)->kind);
  };
  const std::string client = ctx->peer();
  spdlog::info("precompute: {} {} items (shard {}/{}) from {}", total, (*construction)->name,
               req->shard_index(), shards, Quoted(client));

  const auto t0 = Clock::now();
  v1::PrecomputeProgress p;
  p.set_total(total);
  Clock::time_point last_sent{};
  bool client_gone = false;
  struct Outstanding {
    storage::SetKey key;
    std::unique_ptr<Ticket> ticket;
  };
  std::deque<Outstanding> outstanding;
  // How far the items still running are, each by its share of iterations.
  auto running_fraction = [&] {
    double f = 0.0;
    for (const Outstanding& o : outstanding) {
      const JobView v = o.ticket->View();
      if (v.state == JobView::State::kDone) continue;
      if (v.progress.max_iterations > 0) {
        f += std::min(1.0, static_cast<double>(v.progress.iteration) / v.progress.max_iterations);
      }
    }
    return f;
  };
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
    p.set_running_fraction(running_fraction());
    last_sent = Clock::now();
    if (!writer->Write(p)) client_gone = true;
  };
  // The total goes out at once, and while items run an update at least
  // twice a second carrying how far the running items are (an optimization
  // at N = 65536 takes seconds to minutes), so a bar keeps moving.
  constexpr auto kHeartbeat = std::chrono::milliseconds(500);
  auto heartbeat = [&] {
    if (Clock::now() - last_sent >= kHeartbeat) send(nullptr, "", true);
  };
  send(nullptr, "", true);

  // Enough concurrent items to keep every worker busy; the batch never fills
  // the queue, so interactive requests always find room.
  const size_t window = static_cast<size_t>(config_.workers);
  // With several workers the roots go first: a warm item (one with a
  // lineage parent) goes to a wait list, and a free worker reads ahead for
  // the next root before it takes the first waiting item whose parent is
  // done. A warm item must not start before its parent in this batch is done
  // (the job would optimize that parent a second time as its ancestor), and
  // the roots, cold and several times a warm step's length, all start early
  // so that the batch ends on warm steps: taking a ready child before the
  // next root left the last root running alone at the end (at N = 65536 one
  // core idled 172 s of a 1355 s fill; bench/results/
  // lineage_schedule_replay.md).
  // `unresolved` names the items outstanding or waiting. Parents come
  // before children in the order, so the first waiting item's parent is
  // always outstanding or done. The wait list is bounded: beyond it the
  // batch takes waiting items instead of reading ahead.
  constexpr size_t kMaxWaiting = 4096;
  struct Waiting {
    storage::SetKey key;
    std::string parent;  // KeyString of its lineage parent
  };
  std::deque<Waiting> waiting;
  std::unordered_set<std::string> unresolved;
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
      unresolved.erase(KeyString(it->key));
      send(&it->key, error, true);
      it = outstanding.erase(it);
    }
  };
  auto wait_a_little = [&] {
    if (outstanding.empty()) {
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
    } else {
      outstanding.front().ticket->Wait(kPoll);
    }
    heartbeat();
  };
  // The next item to submit: the next root of the waiting items' N in order
  // that is not stored already (those are counted here), else the first
  // waiting one whose parent is done. Nothing when every remaining item waits
  // or none is left. One worker takes the items in order.
  uint64_t j = 0;
  auto next_item = [&]() -> std::optional<storage::SetKey> {
    while (j < total && waiting.size() < kMaxWaiting) {
      // Roots first within one N: the next N's roots wait until every key of
      // this one has started, so that sizes still finish in the order asked.
      if (!waiting.empty() && n_of(j) != waiting.front().key.n) break;
      // A run over many stored items still notices a client that left.
      if (ctx->IsCancelled() || client_gone) return std::nullopt;
      storage::SetKey key = item(j++);
      auto stored = scheduler_->producer().IsStored(key);
      if (stored.ok() && *stored) {
        p.set_cached_already(p.cached_already() + 1);
        send(&key, "", false);
        continue;
      }
      if (window > 1) {
        // Every warm key goes through the wait list, its parent done or
        // not, so that the roots read after it start first.
        if (const auto parent = scheduler_->producer().LineageParentKey(key)) {
          unresolved.insert(KeyString(key));
          waiting.push_back({std::move(key), KeyString(*parent)});
          continue;
        }
      }
      return key;
    }
    for (auto it = waiting.begin(); it != waiting.end(); ++it) {
      if (unresolved.count(it->parent) == 0) {
        storage::SetKey key = std::move(it->key);
        waiting.erase(it);
        return key;
      }
    }
    return std::nullopt;
  };

  for (;;) {
    reap();
    if (ctx->IsCancelled() || client_gone) return ClientGone(ctx);
    if (outstanding.size() >= window) {
      wait_a_little();
      continue;
    }
    std::optional<storage::SetKey> key = next_item();
    if (ctx->IsCancelled() || client_gone) return ClientGone(ctx);
    if (!key) {
      if (outstanding.empty() && waiting.empty()) break;
      // Not expected (a waiting item's parent is outstanding or done), but
      // never stall: the front item then optimizes its ancestors itself.
      if (outstanding.empty()) {
        key = std::move(waiting.front().key);
        waiting.pop_front();
      } else {
        wait_a_little();
        continue;
      }
    }
    for (;;) {
      auto ticket = scheduler_->Acquire(*key, Priority::kBatch, client);
      if (ticket.ok()) {
        unresolved.insert(KeyString(*key));
        outstanding.push_back({std::move(*key), std::move(ticket).value()});
        break;
      }
      if (ticket.status().code() == Status::Code::kResourceExhausted) {
        // Interactive work filled the queue; wait for room.
        wait_a_little();
        reap();
        if (ctx->IsCancelled() || client_gone) return ClientGone(ctx);
        continue;
      }
      if (ticket.status().code() == Status::Code::kUnavailable) return ToGrpc(ticket.status());
      unresolved.erase(KeyString(*key));
      p.set_failed(p.failed() + 1);
      send(&*key, ticket.status().message(), true);
      break;
    }
  }
  send(nullptr, "", true);
  spdlog::info("precompute finished: {} optimized, {} cached already, {} failed in {:.1f} s",
               p.done(), p.cached_already(), p.failed(), Since(t0));
  return grpc::Status::OK;
}
}  // namespace alignset::server

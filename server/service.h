#pragma once

#include <atomic>
#include <memory>
#include <mutex>
#include <string>
#include <unordered_map>

#include "alignset/v1/alignset.grpc.pb.h"
#include "server/config.h"
#include "server/event_loop.h"
#include "server/metrics.h"
#include "server/scheduler.h"
#include "storage/set_cache.h"

namespace alignset::server {

class WatchCall;

// The service's base: the two calls that can wait for an optimization run on
// gRPC's callback API, the rest on the synchronous one.
using AlignSetServiceBase = v1::AlignSet::WithCallbackMethod_GetAlignedSet<
    v1::AlignSet::WithCallbackMethod_WatchAlignedSet<v1::AlignSet::Service>>;

// The alignset.v1.AlignSet service.
//
// Threads: a GetAlignedSet or WatchAlignedSet call that waits for an
// optimization holds no thread. Its ticket calls back when the job is done,
// and one event loop thread builds the responses and paces every watch
// stream (server/watch_pacer.h); a client that cancels or reaches its
// deadline is told by gRPC (OnCancel) and its ticket is released. At most
// --max-waiting-calls such calls wait at once (more: RESOURCE_EXHAUSTED).
// Precompute streams, which do hold a thread, are capped by
// --max-precompute-streams. The other calls are short and synchronous.
class AlignSetService final : public AlignSetServiceBase {
 public:
  // `token` empty: no authentication. Otherwise every call must carry
  // metadata "authorization: Bearer <token>" or gets UNAUTHENTICATED.
  AlignSetService(const ServerConfig& config, std::string db_path, std::string token,
                  storage::SetCache* cache, Scheduler* scheduler, Metrics* metrics);
  ~AlignSetService() override;

  grpc::ServerUnaryReactor* GetAlignedSet(grpc::CallbackServerContext* ctx,
                                          const v1::AlignedSetRequest* req,
                                          v1::AlignedSetResponse* resp) override;
  grpc::ServerWriteReactor<v1::WatchEvent>* WatchAlignedSet(grpc::CallbackServerContext* ctx,
                                                             const v1::AlignedSetRequest* req) override;
  // In server/service_batch.cc: the GetAlignedSet path for many items, one
  // status per item. Synchronous: a batch holds a thread while it waits, so
  // at most --max-batch-calls run at once.
  grpc::Status GetAlignedSets(grpc::ServerContext* ctx, const v1::AlignedSetsRequest* req,
                              v1::AlignedSetsResponse* resp) override;
  grpc::Status Precompute(grpc::ServerContext* ctx, const v1::PrecomputeRequest* req,
                          grpc::ServerWriter<v1::PrecomputeProgress>* writer) override;
  grpc::Status GetSamples(grpc::ServerContext* ctx, const v1::SamplesRequest* req,
                          v1::SamplesResponse* resp) override;
  grpc::Status GetCacheStats(grpc::ServerContext* ctx, const v1::CacheStatsRequest* req,
                             v1::CacheStatsResponse* resp) override;
  grpc::Status ListCachedSets(grpc::ServerContext* ctx, const v1::ListCachedSetsRequest* req,
                              v1::ListCachedSetsResponse* resp) override;
  grpc::Status GetMetrics(grpc::ServerContext* ctx, const v1::MetricsRequest* req,
                          v1::MetricsResponse* resp) override;
  grpc::Status EstimateDirection(grpc::ServerContext* ctx, const v1::EstimateDirectionRequest* req,
                                 v1::EstimateDirectionResponse* resp) override;

  // OK when no token is required or the call carries it; otherwise
  // UNAUTHENTICATED, counted in requests_unauthenticated. Also guards the
  // reflection service.
  grpc::Status Authorize(grpc::ServerContextBase* ctx) const;

  // Calls waiting for an optimization right now (GetAlignedSet and
  // WatchAlignedSet together).
  int64_t waiting_calls() const { return waiting_calls_.load(); }
  // The metrics as GetMetrics reports them.
  void FillMetrics(v1::MetricsResponse* out) const;

 private:
  friend class GetCall;
  friend class WatchCall;

  grpc::Status Invalid(const Status& s, const char* rpc) const;
  // `grid`: the key space whose order `index` is reported in (a key off
  // whole degrees is always in the quarter-degree space).
  void FillKey(const storage::SetKey& key, v1::CanonicalKey* out,
               AngleGrid grid = AngleGrid::kWholeDegree) const;
  // An aligned-set request's canonicalization on its grid.
  StatusOr<Canonicalization> Canonicalize(const v1::AlignedSetRequest& req) const;
  // The canonical key the request asks for: its realization and
  // construction checked (INVALID_ARGUMENT), the profile its construction's.
  StatusOr<storage::SetKey> KeyOf(const v1::AlignedSetRequest& req,
                                  const Canonicalization& canon) const;
  void FillSet(const Canonicalization& canon, const storage::SetKey& key,
               const CanonicalEntry& entry, bool from_cache, v1::AlignedSetResponse* out) const;
  // Takes a waiting slot; false (and nothing taken) at --max-waiting-calls.
  bool TakeWaitingSlot();
  void ReturnWaitingSlot() { waiting_calls_.fetch_sub(1); }
  void TickWatches();
  void AddWatch(const std::shared_ptr<WatchCall>& call);
  void RemoveWatch(const WatchCall* call);

  const ServerConfig config_;
  const std::string db_path_;
  const std::string token_;
  storage::SetCache* cache_;
  Scheduler* scheduler_;
  Metrics* metrics_;
  std::atomic<int64_t> waiting_calls_{0};
  std::atomic<int> precompute_streams_{0};
  std::atomic<int> batch_calls_{0};
  std::mutex watches_mu_;
  std::unordered_map<const WatchCall*, std::weak_ptr<WatchCall>> watches_;
  // Last: its thread runs closures that use everything above.
  std::unique_ptr<EventLoop> loop_;
};

// alignset Status -> gRPC status, code for code.
grpc::Status ToGrpc(const Status& s);

}  // namespace alignset::server

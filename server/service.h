#pragma once

#include <string>

#include "alignset/v1/alignset.grpc.pb.h"
#include "server/config.h"
#include "server/metrics.h"
#include "server/scheduler.h"
#include "storage/set_cache.h"

namespace alignset::server {

// The alignset.v1.AlignSet service on gRPC's synchronous API. Handlers that
// wait for an optimization poll their context every 50 ms, so a client that
// cancels or reaches its deadline stops waiting promptly (its ticket is
// released; see Scheduler for what happens to the optimization).
class AlignSetService final : public v1::AlignSet::Service {
 public:
  // `token` empty: no authentication. Otherwise every call must carry
  // metadata "authorization: Bearer <token>" or gets UNAUTHENTICATED.
  AlignSetService(const ServerConfig& config, std::string db_path, std::string token,
                  storage::SetCache* cache, Scheduler* scheduler, Metrics* metrics);

  grpc::Status GetAlignedSet(grpc::ServerContext* ctx, const v1::AlignedSetRequest* req,
                             v1::AlignedSetResponse* resp) override;
  grpc::Status WatchAlignedSet(grpc::ServerContext* ctx, const v1::AlignedSetRequest* req,
                               grpc::ServerWriter<v1::WatchEvent>* writer) override;
  // In server/service_batch.cc: a loop over the GetAlignedSet path, one
  // status per item.
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

 private:
  grpc::Status Authorize(grpc::ServerContext* ctx) const;
  grpc::Status Invalid(const Status& s, const char* rpc) const;
  void FillMetrics(v1::MetricsResponse* out) const;
  // `grid`: the key space whose order `index` is reported in (a key off
  // whole degrees is always in the quarter-degree space).
  void FillKey(const storage::SetKey& key, v1::CanonicalKey* out,
               AngleGrid grid = AngleGrid::kWholeDegree) const;
  // An aligned-set request's canonicalization on its grid.
  StatusOr<Canonicalization> Canonicalize(const v1::AlignedSetRequest& req) const;
  void FillSet(const Canonicalization& canon, const storage::SetKey& key,
               const CanonicalEntry& entry, bool from_cache, v1::AlignedSetResponse* out) const;

  const ServerConfig config_;
  const std::string db_path_;
  const std::string token_;
  storage::SetCache* cache_;
  Scheduler* scheduler_;
  Metrics* metrics_;
};

// alignset Status -> gRPC status, code for code.
grpc::Status ToGrpc(const Status& s);

}  // namespace alignset::server

#pragma once

#include <cstdint>
#include <functional>
#include <string>

#include "core/align/canonical.h"
#include "core/optimize/optimizer.h"
#include "core/spectral/spectral_engine.h"
#include "core/util/status.h"

namespace alignset::server {

inline constexpr const char* kDefaultListenAddress = "127.0.0.1:50051";

// Everything alignset-server can be told. Each flag --name has an environment
// variable ALIGNSET_NAME (upper case, '-' -> '_'); a flag wins over its
// variable, a variable over the default.
struct ServerConfig {
  std::string listen = kDefaultListenAddress;
  std::string db_path;  // empty: storage::DefaultDatabasePath()
  int workers = 1;
  int threads_per_worker = 0;  // <= 0: ThreadsPerWorker shares the cores out
  uint32_t max_n = 65536;
  int max_iterations = 0;  // 0: DefaultIterationBudget(N)
  double warm_budget = OptimizerOptions{}.warm_budget_fraction;  // WarmStartOptions
  int64_t warm_min_n = OptimizerOptions{}.warm_min_points;       // UsesKeyLineage
  EngineKind engine = EngineKind::kAuto;
  uint64_t seed = 1;
  // Optimizations waiting for a worker; a request needing one more gets
  // RESOURCE_EXHAUSTED.
  int max_queue = 256;
  // Fairness (Scheduler): a client (a connection) may have this many
  // optimizations waiting; a running optimization yields its worker to
  // another client's waiting work after this many milliseconds; at most this
  // many paused optimizations are held in memory.
  int max_queue_per_client = 64;
  int time_slice_ms = 500;
  int max_paused = 16;
  // GetAlignedSet / WatchAlignedSet calls that may wait at once (they hold
  // no thread, but memory), and Precompute streams and GetAlignedSets
  // batches (each holds a thread).
  int max_waiting_calls = 10000;
  int max_precompute_streams = 4;
  int max_batch_calls = 16;
  // PRAGMA quick_check of the cache file at start (in the background).
  int quick_check = 1;
  // Prometheus text exposition on HOST:PORT (GET /metrics); empty: off.
  // With --token-file it takes the same bearer token.
  std::string metrics_listen;
  // A read-only replica: the cache file is opened read-only and immutable
  // and never written; a miss is NOT_FOUND naming the key, or, with
  // fill_from (HOST:PORT of a writer), asked of the writer and kept in
  // memory only. Precompute is refused (FAILED_PRECONDITION).
  bool read_only = false;
  std::string fill_from;
  // With fill_from: speak TLS to the writer, trusting this PEM root
  // certificate, and check the writer's certificate for this name (default:
  // the host of fill_from).
  std::string fill_tls_ca;
  std::string fill_tls_name;
  double fill_timeout_seconds = 600.0;
  // A writer's bound on its cache file, in bytes (0: none): the least
  // recently served sets are evicted to stay under it.
  int64_t max_cache_bytes = 0;
  // Decoded canonical sets (and their encoded alignments) kept in memory.
  int64_t memory_cache_mb = 512;
  // The aligned-lattice search's per-direction terms kept between lattice
  // keys (core/optimize/lattice_term_cache.h); 0 keeps none.
  int64_t lattice_terms_mb = 128;
  // Largest request message accepted (larger: RESOURCE_EXHAUSTED from gRPC).
  int64_t max_request_bytes = 1 << 20;
  std::string tls_cert;  // PEM; both or neither of cert and key
  std::string tls_key;
  std::string token_file;  // one bearer token; empty: no authentication
  // Written with the bound port once listening (for --listen host:0).
  std::string port_file;
  std::string log_level = "info";
  // The grid one-direction requests are served on when they do not choose:
  // quarter degrees (--angle-step 0.25, 181 keys) or whole degrees (1, the
  // 46 keys of Algorithm 1).
  AngleGrid angle_grid = AngleGrid::kQuarterDegree;
  // Seconds that running work may take to finish after SIGTERM/SIGINT before
  // in-flight calls are cancelled.
  double shutdown_grace_seconds = 5.0;
};

// Looks up an environment variable; nullptr when unset.
using EnvLookup = std::function<const char*(const char*)>;

// Parses argv (after the program name) over the environment. --help yields
// NotFound with the usage text as its message.
StatusOr<ServerConfig> ParseServerConfig(int argc, char** argv, const EnvLookup& env);
std::string ServerUsage();

// Threads each optimization worker gets: `configured` when positive, else
// the cores divided among the workers (at least one), so that concurrent
// optimizations do not oversubscribe the machine (the engines' thread pools
// spin briefly between loops, which an oversubscribed core turns into lost
// time).
int ThreadsPerWorker(int workers, int configured, unsigned cores);

}  // namespace alignset::server

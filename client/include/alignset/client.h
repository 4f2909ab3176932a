#pragma once

// The alignset client library: a renderer's (or any program's) way to
// alignset-server. Link it with CMake,
//
//   find_package(alignset 0.1 REQUIRED)
//   target_link_libraries(my_renderer PRIVATE alignset::client)
//
// or with pkg-config (`pkg-config --cflags --libs alignset`). No gRPC or
// protobuf header is included here; the library links them.

#include <alignset/point_set.h>
#include <alignset/status.h>
#include <alignset/version.h>

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace alignset {

// Where the server listens unless told otherwise (alignset-server --listen).
inline constexpr const char* kDefaultServerAddress = "127.0.0.1:50051";

// How to reach an alignset server.
struct ConnectOptions {
  std::string address = kDefaultServerAddress;
  // PEM file of the root certificate(s) to trust; empty: plaintext.
  std::string tls_ca_file;
  // Overrides the name checked against the server's certificate (tests with
  // a self-signed certificate for "localhost" reached as 127.0.0.1).
  std::string tls_server_name;
  // Sent as "authorization: Bearer <token>" on every call when non-empty.
  std::string token;
  // Default deadline of each unary call in seconds (CallOptions overrides it
  // per call); 0: none (GetAlignedSet then waits for as long as the
  // optimization takes). This and the two below are at most 1e9 s (a clock
  // reading past that overflows); Connect or the call refuses others with
  // INVALID_ARGUMENT.
  double timeout_seconds = 0.0;
  // How long a call waits for a connection to the server (reconnecting
  // every 0.1 to 1 s), and a unary call that failed because its connection
  // did is sent again once the server is back: rides out a server restart
  // or a full accept backlog. Past it the call fails UNAVAILABLE. Bounded by
  // the call's own deadline; 0: no wait (gRPC's few quick retries only).
  double connect_timeout_seconds = 2.0;
  // A connection of its own instead of one shared with other clients of the
  // process (load tests).
  bool separate_connection = false;
};

// Per-call settings.
struct CallOptions {
  // Deadline of this call in seconds from its start; overrides
  // ConnectOptions::timeout_seconds, and applies to streaming calls too
  // (which otherwise have none). 0: no deadline. Past it the call fails with
  // DEADLINE_EXCEEDED, and an optimization nobody else waits for is dropped.
  std::optional<double> timeout_seconds;
};

// Everything the server says about a served set (see alignset.proto).
struct SetInfo {
  std::vector<double> requested_deg;
  std::vector<int> served_deg;          // nearest whole degrees
  std::vector<double> served_exact_deg; // exactly (30.25 on the quarter-degree grid)
  double phi1_exact = 0.0;              // the key's first angle exactly
  int steps_per_degree = 1;             // the key space key_index counts in (1 or 4)
  uint32_t n = 0;
  int direction_count = 1;
  int phi1 = 0;
  int phi2 = 0;
  std::string profile;
  uint64_t key_index = 0;
  std::string key_text;
  bool swapped = false;
  bool inverted = false;
  bool inverted_y = false;
  double loss_total = 0.0;
  double loss_spectrum = 0.0;
  double loss_sw = 0.0;
  double length = 0.0, width = 0.0, radius = 0.0;
  int max_iterations = 0;
  double learning_rate = 0.0;
  double sw_weight = 0.0;
  uint64_t seed = 0;  // this set's own seed (its realization's)
  uint32_t realization = 0;
  int algorithm_version = 0;
  bool from_cache = false;
  double optimize_seconds = 0.0;
  int iterations = 0;
  std::string engine;
  // "optimized", "lattice", "net" or "tent-lattice" (SetRequest::construction). A lattice
  // has engine "lattice", iterations and losses 0, no optimization
  // parameters, seed = its realization, algorithm_version the lattice
  // construction's; a net likewise with engine "net".
  std::string construction = "optimized";
  // For a lattice or tent-lattice: the served set's generator g (aligned
  // already): the set is {frac(i (1, g) / N + s)} for some shift s, folded
  // after the shift for a tent-lattice. A renderer draws its own s per
  // pixel with ShiftedLatticePoints (<alignset/lattice_points.h>). 0 otherwise,
  // and from a server too old to send it.
  uint32_t lattice_generator = 0;
};

struct AlignedSet {
  PointSet points;
  SetInfo info;
  // The points exactly as they came over the wire (16 bytes per point).
  std::string raw;
};

// One set: N, one or two directions (degrees), and which of the key's
// independent sets (realization 0 .. kMaxRealization; 0 is the set the key
// always had, each other one is optimized from its own seed).
struct SetRequest {
  static constexpr uint32_t kMaxRealization = 63;
  uint32_t n = 0;
  std::vector<double> directions_deg;
  uint32_t realization = 0;
  // The grid one direction is served on: 0 the server's default
  // (--angle-step, quarter degrees unless set), 1 whole degrees (the 46
  // keys), 4 quarter degrees (181 keys). Two directions: whole degrees.
  uint32_t steps_per_degree = 0;
  // How the set is made: "" or "optimized" (the default, the optimized
  // sets), "lattice" (an aligned rank-1 lattice), "tent-lattice" (an
  // aligned rank-1 lattice folded by the tent map) or "net" (an aligned
  // (0,m,2)-net, N a power of two), each cached apart from the others.
  // Another name: INVALID_ARGUMENT from the server. A server too old to
  // know constructions would answer with an optimized set; the client then
  // fails the call with FAILED_PRECONDITION instead.
  std::string construction = "";
};

// One answer of a batch: the set, or why this item has none. Items fail on
// their own (a bad N, a full queue) without failing the batch.
struct BatchItem {
  Status status;
  AlignedSet set;  // when status.ok()
};

// The most items one batch call may carry (the server refuses more with
// INVALID_ARGUMENT), and the most points in all.
inline constexpr size_t kMaxBatchItems = 256;
inline constexpr uint64_t kMaxBatchPoints = uint64_t{1} << 24;

// One event of WatchAlignedSet before the set arrives.
struct WatchUpdate {
  bool queued = false;  // true: waiting at `queue_position`; false: running
  uint32_t queue_position = 0;
  int iteration = 0;
  int max_iterations = 0;
  double loss = 0.0;
  double learning_rate = 0.0;
  double elapsed_seconds = 0.0;
};

struct PrecomputeSpec {
  std::vector<uint32_t> n;
  int space = 1;  // 1: the one-direction keys, 2: the 4141 pairs, 0: `keys`
  std::vector<std::vector<int>> keys;
  uint32_t shard_index = 0;
  uint32_t shard_count = 1;
  // Space 1's grid: 1 (or 0), the 46 whole-degree keys; 4, the 181
  // quarter-degree keys in their own order (also the grid of explicit
  // one-direction keys).
  uint32_t steps_per_degree = 1;
  // Realizations 0 .. realizations-1 of every key (at most
  // SetRequest::kMaxRealization + 1).
  uint32_t realizations = 1;
  // The construction of every item, as SetRequest::construction.
  std::string construction = "";
};

struct PrecomputeUpdate {
  uint64_t total = 0, done = 0, cached_already = 0, failed = 0, remaining = 0;
  // The items being optimized now, each by the fraction of its iterations
  // done: total - remaining + running_fraction moves within a long item.
  double running_fraction = 0.0;
  double elapsed_seconds = 0.0;
  double estimated_seconds_left = -1.0;
  std::string last_key;
  std::string last_error;
};

struct ServiceMetrics {
  uint64_t requests_get = 0, requests_watch = 0, requests_precompute = 0, requests_samples = 0,
           requests_invalid = 0, requests_estimate = 0;
  uint64_t cache_hits_memory = 0, cache_hits_db = 0, cache_misses = 0, corrupt_rows = 0;
  uint64_t optimizations_started = 0, optimizations_completed = 0, optimizations_cancelled = 0,
           optimizations_failed = 0, shared_waits = 0, rejected_queue_full = 0;
  uint32_t queue_length = 0, running = 0;
  // Fairness and bounds: jobs waiting with a paused state and the slices that
  // yielded a worker, calls waiting for a set now, what the per-client and
  // waiting-call limits refused, calls refused for a missing token.
  uint32_t paused = 0, waiting_calls = 0;
  uint64_t optimizations_paused = 0, rejected_client_limit = 0, rejected_waiting_limit = 0,
           requests_unauthenticated = 0;
  // The file's health: integrity errors seen, sets served but not written.
  uint64_t database_integrity_errors = 0, sets_not_stored = 0;
  double optimize_seconds_total = 0.0, optimize_seconds_max = 0.0, uptime_seconds = 0.0;
  // A read-only replica (--read-only): misses it answered NOT_FOUND (no
  // --fill-from) and sets its writer filled (--fill-from, kept in memory).
  bool read_only = false;
  uint64_t replica_misses = 0, sets_filled = 0;
  // A bounded file (--max-cache-bytes; 0: unbounded): sets evicted (least
  // recently served first), their estimated bytes, the file's size at the
  // last look, background vacuum passes.
  int64_t max_cache_bytes = 0, cache_file_bytes = 0;
  uint64_t cache_evictions = 0, cache_evicted_bytes = 0, cache_vacuums = 0;
  // Memory, in bytes: the process (resident; malloc's in use and kept free,
  // glibc only) and the caches that hold it, each against its bound.
  int64_t resident_bytes = 0, heap_allocated_bytes = 0, heap_free_bytes = 0;
  int64_t resident_anonymous_bytes = 0, resident_file_bytes = 0;  // resident_bytes split
  std::string allocator;  // "jemalloc 5.3.0-..." or "glibc"
  int64_t memory_cache_bytes = 0, memory_cache_capacity_bytes = 0;
  int64_t lattice_terms_bytes = 0, lattice_terms_capacity_bytes = 0;
  int64_t sqlite_memory_bytes = 0, sqlite_memory_peak_bytes = 0;
};

struct CacheInfo {
  int64_t sets = 0, bytes = 0, one_direction_sets = 0, two_direction_sets = 0;
  // The file has damaged pages: the counts cover the readable rows (repair:
  // `alignset cache recover`).
  bool damaged = false;
  std::string database_path;
  std::string profile_hint;
  ServiceMetrics metrics;
};

// One direction estimated by EstimateDirection.
struct EstimatedDirection {
  bool found = false;      // false: no dominant direction (see reason)
  double theta_deg = 0.0;  // [0, 180), spectral convention (edge normal); 0 unless found
  double kappa = 0.0;      // fitted von Mises concentration (doubled angles)
  double confidence = 0.0; // share of the spectral energy in the fitted lobe
  double contrast = 0.0;   // lobe energy over an isotropic spectrum's
  std::string reason;
};

struct DirectionReply {
  EstimatedDirection first;
  bool has_second = false;
  EstimatedDirection second;
  double max_radius = 0.0;
};

struct CachedKey {
  uint32_t n = 0;
  int direction_count = 1;
  int phi1 = 0, phi2 = 0;
  std::string profile;
  std::string text;
};

// A client of alignset.v1.AlignSet; one channel, safe to share across
// threads. Failures come back as Status whose message starts with the gRPC
// code name ("INVALID_ARGUMENT: n = 0 ..."); the code maps onto Status codes
// where one fits (UNAUTHENTICATED and PERMISSION_DENIED become
// kInvalidArgument, UNIMPLEMENTED and UNKNOWN kInternal).
class ServiceClient {
 public:
  static StatusOr<std::unique_ptr<ServiceClient>> Connect(const ConnectOptions& options);
  ~ServiceClient();

  // The aligned set for N points and one or two directions (degrees, the
  // spectral direction = the edge normal). Blocks until it exists.
  StatusOr<AlignedSet> GetAlignedSet(uint32_t n, const std::vector<double>& directions_deg,
                                     const CallOptions& call = {});
  // The same for any realization.
  StatusOr<AlignedSet> GetAlignedSet(const SetRequest& request, const CallOptions& call = {});
  // Many sets in one call, in request order, each with its own status; the
  // call itself fails only when the request as a whole is refused (more than
  // kMaxBatchItems items, ...), the server is unreachable or the deadline
  // passes. Optimizations of missing sets run in parallel on the server.
  StatusOr<std::vector<BatchItem>> GetAlignedSets(const std::vector<SetRequest>& items,
                                                  const CallOptions& call = {});
  // The whole one-direction space of N in one call: the 46 canonical sets,
  // directions 0, 1, ..., 45 degrees in that order (every other direction is
  // one of them swapped and/or mirrored; see alignset.proto), all of one
  // realization.
  StatusOr<std::vector<BatchItem>> GetOneDirectionSpace(uint32_t n, uint32_t realization = 0,
                                                        const CallOptions& call = {});
  // The same space in a construction (SetRequest::construction): an item a
  // server without constructions answers with another one fails with
  // FAILED_PRECONDITION.
  StatusOr<std::vector<BatchItem>> GetOneDirectionSpace(uint32_t n, uint32_t realization,
                                                        const std::string& construction,
                                                        const CallOptions& call = {});
  // Streams queue position and progress to `on_update`, then returns the set.
  StatusOr<AlignedSet> WatchAlignedSet(uint32_t n, const std::vector<double>& directions_deg,
                                       const std::function<void(const WatchUpdate&)>& on_update,
                                       const CallOptions& call = {});
  StatusOr<AlignedSet> WatchAlignedSet(const SetRequest& request,
                                       const std::function<void(const WatchUpdate&)>& on_update,
                                       const CallOptions& call = {});
  // Streams progress until the request's items are all resolved.
  StatusOr<PrecomputeUpdate> Precompute(const PrecomputeSpec& spec,
                                        const std::function<void(const PrecomputeUpdate&)>& on_update,
                                        const CallOptions& call = {});
  StatusOr<PointSet> GetSamples(const std::string& sampler, uint32_t n, uint64_t seed,
                                std::optional<double> shear_deg, const CallOptions& call = {});
  StatusOr<CacheInfo> GetCacheStats(const CallOptions& call = {});
  StatusOr<ServiceMetrics> GetMetrics(const CallOptions& call = {});
  StatusOr<std::vector<CachedKey>> ListCachedSets(uint32_t n, const std::string& profile,
                                                  uint32_t limit, const CallOptions& call = {});
  // The principal direction(s) of an integrand: a grid of values (width x
  // height, values[j * width + i] = f((i + 1/2) / width, (j + 1/2) / height),
  // rows along y) or scattered samples f(points[j]) = values[j]; `second`
  // also asks for a second direction. Then GetAlignedSet(n, {theta}).
  StatusOr<DirectionReply> EstimateDirection(int width, int height,
                                             const std::vector<double>& values, bool second,
                                             const CallOptions& call = {});
  StatusOr<DirectionReply> EstimateDirection(const PointSet& points,
                                             const std::vector<double>& values, bool second,
                                             const CallOptions& call = {});
  // The standard health service: true when the server reports SERVING.
  StatusOr<bool> Healthy(const CallOptions& call = {});

  struct Impl;

 private:
  explicit ServiceClient(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

// Decodes packed little-endian float64 pairs; INVALID_ARGUMENT when the byte
// count is not 16 * expected_n or a coordinate lies outside [0, 1).
StatusOr<PointSet> DecodePoints(const std::string& bytes, uint32_t expected_n);

}  // namespace alignset

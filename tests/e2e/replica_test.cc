// Serving a render farm (issue 29): read-only replicas over a shipped cache
// file, a writer with a bounded file, and the metrics endpoint behind the
// bearer token. Every test runs real alignset-server processes on loopback.
#include <grpcpp/grpcpp.h>
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <filesystem>
#include <fstream>
#include <chrono>
#include <sstream>
#include <thread>

#include "alignset/v1/alignset.grpc.pb.h"
#include "grpc/health/v1/health.grpc.pb.h"
#include "tests/e2e/e2e_util.h"
#include "tests/e2e/server_process.h"

namespace alignset::e2e {
namespace {

namespace fs = std::filesystem;

const std::vector<std::string> kFast = {"--max-iterations", "30", "--workers", "1",
                                        "--threads-per-worker", "1", "--max-n", "4096"};

std::vector<std::string> With(std::vector<std::string> a, const std::vector<std::string>& b) {
  a.insert(a.end(), b.begin(), b.end());
  return a;
}

// What a directory holds: names, sizes and modification times.
std::string Listing(const std::string& dir) {
  std::vector<std::string> rows;
  for (const auto& e : fs::directory_iterator(dir)) {
    struct stat st {};
    ::stat(e.path().c_str(), &st);
    rows.push_back(e.path().filename().string() + " " + std::to_string(st.st_size) + " " +
                   std::to_string(st.st_mtim.tv_sec) + "." + std::to_string(st.st_mtim.tv_nsec));
  }
  std::sort(rows.begin(), rows.end());
  std::string out;
  for (const auto& r : rows) out += r + "\n";
  return out;
}

grpc::Status Get(v1::AlignSet::Stub* stub, uint32_t n, std::vector<double> dirs, v1::AlignedSetResponse* resp,
                 uint32_t realization = 0) {
  grpc::ClientContext ctx;
  ctx.set_deadline(std::chrono::system_clock::now() + std::chrono::seconds(60));
  v1::AlignedSetRequest req = SetRequest(n, std::move(dirs));
  req.set_realization(realization);
  return stub->GetAlignedSet(&ctx, req, resp);
}

// A writer fills `dir`/cache.sqlite with the N = 64 one-direction space
// (46 sets) plus one two-direction set, and stops (so the file is whole:
// its WAL checkpointed into it and removed, as a shipped file is).
void MakeShippedCache(const std::string& dir) {
  ServerProcess writer(dir, kFast);
  ASSERT_EQ(writer.error(), "");
  PrecomputeOneDirection(writer.address());
  auto stub = OwnStub(writer.address());
  v1::AlignedSetResponse resp;
  ASSERT_TRUE(Get(stub.get(), 64, {20, 110}, &resp).ok());
  ASSERT_EQ(writer.Stop(SIGTERM), 0);
  ASSERT_FALSE(fs::exists(dir + "/cache.sqlite-wal"));
}

TEST(Replica, RefusesEveryWritePathAndNeverModifiesItsFile) {
  TempDir shipped, replica_dir;
  MakeShippedCache(shipped.path());
  const std::string file = shipped.path() + "/cache.sqlite";
  const std::string before = ReadText(file);
  const std::string listing = Listing(shipped.path());
  ASSERT_GT(before.size(), 0u);
  {
    ServerProcess replica(replica_dir.path(), With(kFast, {"--read-only", "--db", file}));
    ASSERT_EQ(replica.error(), "");
    auto stub = OwnStub(replica.address());
    v1::AlignedSetResponse resp;
    // A stored set is served, from the file.
    ASSERT_TRUE(Get(stub.get(), 64, {30}, &resp).ok());
    EXPECT_TRUE(resp.metadata().from_cache());
    // A miss (another N, a realization never made, a pair never asked) is
    // NOT_FOUND naming the key; nothing is optimized.
    for (auto [n, dirs, r] : {std::tuple{128u, std::vector<double>{30}, 0u}, std::tuple{64u, std::vector<double>{30}, 5u},
                              std::tuple{64u, std::vector<double>{20, 120}, 0u}}) {
      const grpc::Status s = Get(stub.get(), n, dirs, &resp, r);
      EXPECT_EQ(s.error_code(), grpc::StatusCode::NOT_FOUND) << s.error_message();
      EXPECT_NE(s.error_message().find("n=" + std::to_string(n)), std::string::npos) << s.error_message();
      EXPECT_NE(s.error_message().find("read-only replica"), std::string::npos) << s.error_message();
    }
    {  // WatchAlignedSet of a miss
      grpc::ClientContext ctx;
      auto reader = stub->WatchAlignedSet(&ctx, SetRequest(256, {40}));
      v1::WatchEvent e;
      while (reader->Read(&e)) {
      }
      const grpc::Status s = reader->Finish();
      EXPECT_EQ(s.error_code(), grpc::StatusCode::NOT_FOUND) << s.error_message();
    }
    {  // GetAlignedSets: the stored item is served, the missing one NOT_FOUND
      grpc::ClientContext ctx;
      v1::AlignedSetsRequest req;
      *req.add_items() = SetRequest(64, {10});
      *req.add_items() = SetRequest(512, {10});
      v1::AlignedSetsResponse resp2;
      ASSERT_TRUE(stub->GetAlignedSets(&ctx, req, &resp2).ok());
      ASSERT_EQ(resp2.items_size(), 2);
      EXPECT_EQ(resp2.items(0).code(), 0);
      EXPECT_EQ(resp2.items(1).code(), static_cast<int>(grpc::StatusCode::NOT_FOUND));
    }
    {  // `alignset stats` prints the replica's counters as its metrics count them
      const v1::MetricsResponse m = GetMetrics(replica.address());
      EXPECT_TRUE(m.read_only());
      EXPECT_GE(m.replica_misses(), 4u);
      const CommandResult stats = RunCommand(std::string(ALIGNSET_CLI_PATH) + " stats --server " + replica.address());
      EXPECT_EQ(stats.exit_code, 0) << stats.output;
      EXPECT_NE(stats.output.find("replica           yes (read-only), misses " + std::to_string(m.replica_misses()) +
                                  " (NOT_FOUND), filled 0 from the writer"),
                std::string::npos)
          << stats.output;
    }
    {  // Precompute: refused as a whole
      grpc::ClientContext ctx;
      v1::PrecomputeRequest req;
      req.add_n(128);
      req.set_space(v1::ONE_DIRECTION);
      auto reader = stub->Precompute(&ctx, req);
      v1::PrecomputeProgress p;
      while (reader->Read(&p)) {
      }
      const grpc::Status s = reader->Finish();
      EXPECT_EQ(s.error_code(), grpc::StatusCode::FAILED_PRECONDITION) << s.error_message();
      EXPECT_NE(s.error_message().find("read-only"), std::string::npos);
    }
    // The mode, in metrics and in health.
    const v1::MetricsResponse m = GetMetrics(replica.address());
    EXPECT_TRUE(m.read_only());
    EXPECT_EQ(m.replica_misses(), 5u);  // 3 gets, the watch, the batch item
    EXPECT_EQ(m.optimizations_started(), 0u);
    auto health = grpc::health::v1::Health::NewStub(OwnChannel(replica.address()));
    for (auto [service, serving] : {std::pair{"alignset.read-only", true}, std::pair{"alignset.writer", false}}) {
      grpc::ClientContext ctx;
      grpc::health::v1::HealthCheckRequest req;
      req.set_service(service);
      grpc::health::v1::HealthCheckResponse resp3;
      ASSERT_TRUE(health->Check(&ctx, req, &resp3).ok()) << service;
      EXPECT_EQ(resp3.status(), serving ? grpc::health::v1::HealthCheckResponse::SERVING
                                        : grpc::health::v1::HealthCheckResponse::NOT_SERVING)
          << service;
    }
    EXPECT_EQ(replica.Stop(SIGTERM), 0);
  }
  // Byte for byte the same file, and no -wal / -shm (or anything else) made beside it.
  EXPECT_TRUE(ReadText(file) == before) << "the replica changed its cache file";
  EXPECT_EQ(Listing(shipped.path()), listing);
}

TEST(Replica, TwoReplicasServeIdenticalBytesForEveryKey) {
  TempDir shipped, a_dir, b_dir;
  MakeShippedCache(shipped.path());
  const std::string file = shipped.path() + "/cache.sqlite";
  ServerProcess a(a_dir.path(), With(kFast, {"--read-only", "--db", file}));
  ServerProcess b(b_dir.path(), With(kFast, {"--read-only", "--db", file}));
  ASSERT_EQ(a.error(), "");
  ASSERT_EQ(b.error(), "");
  auto sa = OwnStub(a.address());
  auto sb = OwnStub(b.address());
  // Every whole degree maps onto one of the 46 stored keys (some swapped or
  // mirrored): all 180 directions, plus the stored pair.
  std::set<std::string> keys;
  for (int d = 0; d <= 180; ++d) {
    const std::vector<double> dirs = d == 180 ? std::vector<double>{20, 110} : std::vector<double>{double(d)};
    v1::AlignedSetResponse ra, rb;
    ASSERT_TRUE(Get(sa.get(), 64, dirs, &ra).ok()) << d;
    ASSERT_TRUE(Get(sb.get(), 64, dirs, &rb).ok()) << d;
    EXPECT_TRUE(ra.metadata().from_cache());
    EXPECT_EQ(ra.metadata().key().text(), rb.metadata().key().text());
    EXPECT_TRUE(ra.points() == rb.points()) << "direction " << d;
    EXPECT_EQ(ra.points().size(), 64u * 16u);
    keys.insert(ra.metadata().key().text());
  }
  EXPECT_EQ(keys.size(), 47u);
}

TEST(Replica, FillFromAWriterKeepsTheSetInMemoryOnly) {
  TempDir shipped, writer_dir, replica_dir;
  MakeShippedCache(shipped.path());
  const std::string file = shipped.path() + "/cache.sqlite";
  const std::string before = ReadText(file);
  ServerProcess writer(writer_dir.path(), kFast);
  ASSERT_EQ(writer.error(), "");
  ServerProcess replica(replica_dir.path(),
                        With(kFast, {"--read-only", "--db", file, "--fill-from", writer.address()}));
  ASSERT_EQ(replica.error(), "");
  auto rs = OwnStub(replica.address());
  auto ws = OwnStub(writer.address());
  for (const std::vector<double>& dirs : {std::vector<double>{77.25}, std::vector<double>{15, 100}}) {
    v1::AlignedSetResponse from_replica, from_writer;
    ASSERT_TRUE(Get(rs.get(), 128, dirs, &from_replica).ok());
    EXPECT_TRUE(from_replica.metadata().not_stored());  // in memory only
    ASSERT_TRUE(Get(ws.get(), 128, dirs, &from_writer).ok());
    EXPECT_TRUE(from_writer.metadata().from_cache());  // the writer stored what it made for the replica
    EXPECT_TRUE(from_replica.points() == from_writer.points());
    v1::AlignedSetResponse again;
    ASSERT_TRUE(Get(rs.get(), 128, dirs, &again).ok());
    EXPECT_TRUE(again.points() == from_replica.points());
  }
  const v1::MetricsResponse m = GetMetrics(replica.address());
  EXPECT_EQ(m.sets_filled(), 2u);
  EXPECT_EQ(m.optimizations_started(), 0u);
  EXPECT_EQ(replica.Stop(SIGTERM), 0);
  EXPECT_TRUE(ReadText(file) == before);
}

// A replica's fill is cancelled with the call that asked for it: the
// caller's deadline passes while the writer is still optimizing; the
// replica cancels its call to the writer, and the writer, with no one else
// waiting, drops the optimization (before: both went on to the writer's
// end, and the replica's fill timeout).
TEST(Replica, AnInFlightFillIsCancelledWithItsCaller) {
  TempDir shipped, writer_dir, replica_dir;
  MakeShippedCache(shipped.path());
  // Slow enough to be in flight when the caller gives up (seconds at N = 4096).
  ServerProcess writer(writer_dir.path(), {"--max-iterations", "20000", "--workers", "1", "--threads-per-worker", "1",
                                           "--max-n", "4096"});
  ASSERT_EQ(writer.error(), "");
  ServerProcess replica(replica_dir.path(), With(kFast, {"--read-only", "--db", shipped.path() + "/cache.sqlite",
                                                         "--fill-from", writer.address()}));
  ASSERT_EQ(replica.error(), "");
  auto rs = OwnStub(replica.address());
  {
    grpc::ClientContext ctx;
    ctx.set_deadline(std::chrono::system_clock::now() + std::chrono::milliseconds(700));
    v1::AlignedSetResponse resp;
    const grpc::Status s = rs->GetAlignedSet(&ctx, SetRequest(4096, {33}), &resp);
    ASSERT_EQ(s.error_code(), grpc::StatusCode::DEADLINE_EXCEEDED) << s.error_message();
  }
  // The writer's optimization is withdrawn within seconds, not run out.
  const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(20);
  uint64_t writer_cancelled = 0, replica_cancelled = 0;
  while (std::chrono::steady_clock::now() < until) {
    writer_cancelled = GetMetrics(writer.address()).optimizations_cancelled();
    replica_cancelled = GetMetrics(replica.address()).optimizations_cancelled();
    if (writer_cancelled >= 1 && replica_cancelled >= 1) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  EXPECT_GE(replica_cancelled, 1u) << "the replica never cancelled its fill";
  EXPECT_GE(writer_cancelled, 1u) << "the writer never saw its caller leave";
  EXPECT_EQ(GetMetrics(writer.address()).optimizations_completed(), 0u);
  EXPECT_EQ(GetMetrics(replica.address()).sets_filled(), 0u);
  // The replica serves on.
  v1::AlignedSetResponse resp;
  ASSERT_TRUE(Get(rs.get(), 64, {30}, &resp).ok());
}

// --fill-from a writer that serves TLS: the replica trusts the writer's
// certificate (--fill-tls-ca, --fill-tls-name) and fills over TLS; a replica
// that speaks plaintext to the same writer gets no set (UNAVAILABLE) and
// serves on.
TEST(Replica, FillFromAWriterOverTls) {
  TempDir shipped, writer_dir, replica_dir, plain_dir;
  MakeShippedCache(shipped.path());
  const std::string d = writer_dir.path();
  auto gen = RunCommand("openssl req -x509 -newkey ec -pkeyopt ec_paramgen_curve:prime256v1 -nodes "
                        "-days 1 -subj /CN=localhost -addext subjectAltName=DNS:localhost -keyout " +
                        d + "/key.pem -out " + d + "/cert.pem");
  ASSERT_EQ(gen.exit_code, 0) << gen.output;
  ServerProcess writer(writer_dir.path(), With(kFast, {"--tls-cert", d + "/cert.pem", "--tls-key", d + "/key.pem"}));
  ASSERT_EQ(writer.error(), "");
  const std::string file = shipped.path() + "/cache.sqlite";
  ServerProcess replica(replica_dir.path(),
                        With(kFast, {"--read-only", "--db", file, "--fill-from", writer.address(), "--fill-tls-ca",
                                     d + "/cert.pem", "--fill-tls-name", "localhost"}));
  ASSERT_EQ(replica.error(), "");
  auto rs = OwnStub(replica.address());
  v1::AlignedSetResponse resp;
  ASSERT_TRUE(Get(rs.get(), 128, {41}, &resp).ok());
  EXPECT_TRUE(resp.metadata().not_stored());
  EXPECT_EQ(GetMetrics(replica.address()).sets_filled(), 1u);

  ServerProcess plain(plain_dir.path(), With(kFast, {"--read-only", "--db", file, "--fill-from", writer.address()}));
  ASSERT_EQ(plain.error(), "");
  auto ps = OwnStub(plain.address());
  const grpc::Status refused = Get(ps.get(), 128, {41}, &resp);
  EXPECT_EQ(refused.error_code(), grpc::StatusCode::UNAVAILABLE) << refused.error_message();
  ASSERT_TRUE(Get(ps.get(), 64, {30}, &resp).ok());  // serves on
}

TEST(Replica, ConfigurationMistakesAreUsageErrors) {
  const std::string bin = ServerBinary();
  for (const std::string flags : {"--fill-from 127.0.0.1:1", "--read-only --max-cache-bytes 10000000",
                                  "--max-cache-bytes 1000", "--read-only=maybe",
                                  "--metrics-listen 127.0.0.1:70000", "--read-only --fill-tls-ca a.pem",
                                  "--read-only --fill-from 127.0.0.1:1 --fill-tls-name localhost"}) {
    const CommandResult r = RunCommand(bin + " " + flags + " --db /nonexistent/x.sqlite");
    EXPECT_EQ(r.exit_code, 2) << flags << ": " << r.output;
  }
  // A replica of a file that is not there does not start (nothing is created).
  TempDir dir;
  const CommandResult r = RunCommand(bin + " --read-only --listen 127.0.0.1:0 --db " + dir.path() + "/none.sqlite");
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_FALSE(fs::exists(dir.path() + "/none.sqlite"));
}

// --max-cache-bytes: the file stays under the bound, the least recently
// served sets go first, and the evictions show in metrics.
TEST(BoundedCache, EvictionKeepsTheFileUnderTheBoundAndTheMostRecentlyServedSets) {
  TempDir dir;
  const int64_t bound = 256 * 1024;  // about 11 sets of N = 1024 (16 KiB each, 5 pages)
  ServerProcess server(dir.path(), With(kFast, {"--max-cache-bytes", std::to_string(bound),
                                                "--metrics-listen", "127.0.0.1:0"}));
  ASSERT_EQ(server.error(), "");
  auto stub = OwnStub(server.address());
  v1::AlignedSetResponse resp;
  ASSERT_TRUE(Get(stub.get(), 1024, {0}, &resp).ok());  // the set kept hot throughout
  const std::string hot = resp.points();
  for (uint32_t r = 1; r <= 40; ++r) {
    ASSERT_TRUE(Get(stub.get(), 1024, {10}, &resp, r).ok()) << r;
    EXPECT_FALSE(resp.metadata().not_stored()) << r;
    ASSERT_TRUE(Get(stub.get(), 1024, {0}, &resp).ok());  // served again: the most recent
    EXPECT_TRUE(resp.points() == hot);
    const v1::MetricsResponse m = GetMetrics(server.address());
    EXPECT_LE(m.cache_file_bytes(), bound) << "after set " << r;
    EXPECT_LE(static_cast<int64_t>(fs::file_size(server.db_path())), bound) << "after set " << r;
  }
  const v1::MetricsResponse m = GetMetrics(server.address());
  EXPECT_GE(m.cache_evictions(), 25u);
  EXPECT_EQ(m.max_cache_bytes(), bound);
  EXPECT_GT(m.cache_evicted_bytes(), 0u);
  const auto prom = ParsePrometheus(HttpRequest(server.metrics_port(), "GET", "/metrics").body);
  EXPECT_EQ(prom.at("alignset_cache_evictions_total"), static_cast<double>(m.cache_evictions()));
  // `alignset stats` prints the same evictions and the bound.
  const CommandResult stats = RunCommand(std::string(ALIGNSET_CLI_PATH) + " stats --server " + server.address());
  EXPECT_EQ(stats.exit_code, 0) << stats.output;
  EXPECT_NE(stats.output.find(", evictions " + std::to_string(m.cache_evictions()) + " ("), std::string::npos)
      << stats.output;
  EXPECT_NE(stats.output.find("replica           no, misses 0"), std::string::npos) << stats.output;
  // The hot set was never evicted; the first of the realizations was.
  ASSERT_TRUE(Get(stub.get(), 1024, {0}, &resp).ok());
  EXPECT_TRUE(resp.metadata().from_cache());
  ASSERT_TRUE(Get(stub.get(), 1024, {10}, &resp, 1).ok());
  EXPECT_FALSE(resp.metadata().from_cache());
  // Stopped (WAL checkpointed into the file, free pages returned): still under.
  ASSERT_EQ(server.Stop(SIGTERM), 0);
  EXPECT_LE(static_cast<int64_t>(fs::file_size(server.db_path())), bound);
  const CommandResult verify = RunCommand(std::string(ALIGNSET_CLI_PATH) + " cache verify --db " + server.db_path());
  EXPECT_EQ(verify.exit_code, 0) << verify.output;
}

// The least-recently-served order is kept beside the file: a set served
// again just before a restart outlives, after it, the sets made after it
// and not served since (by creation time alone it would go first).
TEST(BoundedCache, TheEvictionOrderSurvivesARestart) {
  TempDir dir;
  const int64_t bound = 256 * 1024;  // about 11 sets of N = 1024
  const std::vector<std::string> flags = With(kFast, {"--max-cache-bytes", std::to_string(bound)});
  v1::AlignedSetResponse resp;
  std::string first;
  {
    ServerProcess server(dir.path(), flags);
    ASSERT_EQ(server.error(), "");
    auto stub = OwnStub(server.address());
    for (uint32_t r = 1; r <= 8; ++r) ASSERT_TRUE(Get(stub.get(), 1024, {10}, &resp, r).ok()) << r;
    ASSERT_TRUE(Get(stub.get(), 1024, {10}, &resp, 1).ok());  // realization 1: now the most recent
    EXPECT_TRUE(resp.metadata().from_cache());
    first = resp.points();
    ASSERT_EQ(server.Stop(SIGTERM), 0);
    ASSERT_TRUE(fs::exists(server.db_path() + ".served"));
  }
  ServerProcess again(dir.path(), flags);
  ASSERT_EQ(again.error(), "");
  auto stub = OwnStub(again.address());
  // Eight more sets: the file holds about 11, so about five of the first
  // eight go, realization 2 (the least recently served) first, 1 last.
  for (uint32_t r = 9; r <= 16; ++r) ASSERT_TRUE(Get(stub.get(), 1024, {10}, &resp, r).ok()) << r;
  EXPECT_GE(GetMetrics(again.address()).cache_evictions(), 3u);
  ASSERT_TRUE(Get(stub.get(), 1024, {10}, &resp, 2).ok());
  EXPECT_FALSE(resp.metadata().from_cache()) << "realization 2 should have been evicted first";
  ASSERT_TRUE(Get(stub.get(), 1024, {10}, &resp, 1).ok());
  EXPECT_TRUE(resp.metadata().from_cache()) << "realization 1 was served last before the restart";
  EXPECT_EQ(resp.points(), first);
}

TEST(MetricsAuth, TheEndpointRefusesARequestWithoutTheTokenWhenOneIsSet) {
  TempDir dir;
  const std::string token_file = dir.path() + "/token";
  std::ofstream(token_file) << "s3cret-token\n";
  ServerProcess server(dir.path(), With(kFast, {"--token-file", token_file, "--metrics-listen", "127.0.0.1:0"}));
  ASSERT_EQ(server.error(), "");
  const HttpReply none = HttpRequest(server.metrics_port(), "GET", "/metrics");
  EXPECT_EQ(none.status, 401) << none.headers;
  EXPECT_NE(none.headers.find("WWW-Authenticate: Bearer"), std::string::npos) << none.headers;
  EXPECT_EQ(none.body.find("alignset_"), std::string::npos);
  const HttpReply wrong = HttpRequest(server.metrics_port(), "GET", "/metrics", "Authorization: Bearer nope\r\n");
  EXPECT_EQ(wrong.status, 401);
  const HttpReply other_path = HttpRequest(server.metrics_port(), "GET", "/", "");
  EXPECT_EQ(other_path.status, 401);
  const HttpReply right =
      HttpRequest(server.metrics_port(), "GET", "/metrics", "Authorization: Bearer s3cret-token\r\n");
  ASSERT_EQ(right.status, 200) << right.headers;
  const auto values = ParsePrometheus(right.body);
  EXPECT_EQ(values.at("alignset_requests_unauthenticated_total"), 3.0);
  EXPECT_EQ(values.at("alignset_read_only"), 0.0);
}

}  // namespace
}  // namespace alignset::e2e

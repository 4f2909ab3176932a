// End-to-end: the real alignset-server binary on loopback. Each test starts
// its own server on a fresh database with small N and few iterations.
#include <grpcpp/grpcpp.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sqlite3.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <fstream>
#include <limits>
#include <thread>

#include "alignset/v1/alignset.grpc.pb.h"
#include <alignset/client.h>
#include "grpc/health/v1/health.grpc.pb.h"
#include "storage/set_cache.h"
#include "tests/e2e/server_process.h"

namespace alignset::e2e {
namespace {

using namespace std::chrono_literals;

// Small sets and few iterations keep every optimization in the tens of
// milliseconds on two cores.
const std::vector<std::string> kFast = {"--max-iterations", "60", "--workers", "2",
                                        "--threads-per-worker", "1", "--max-n", "4096"};

std::vector<std::string> With(std::vector<std::string> a, const std::vector<std::string>& b) {
  a.insert(a.end(), b.begin(), b.end());
  return a;
}

class E2eTest : public ::testing::Test {
 protected:
  void StartServer(const std::vector<std::string>& flags) {
    server_.reset();
    server_ = std::make_unique<ServerProcess>(dir_.path(), flags);
    ASSERT_EQ(server_->error(), "");
  }
  std::unique_ptr<ServiceClient> Client(ConnectOptions o = {}) {
    o.address = server_->address();
    auto c = ServiceClient::Connect(o);
    EXPECT_TRUE(c.ok()) << c.status().message();
    return std::move(c).value();
  }
  std::unique_ptr<v1::AlignSet::Stub> RawStub() {
    grpc::ChannelArguments args;
    args.SetMaxSendMessageSize(-1);
    args.SetMaxReceiveMessageSize(-1);
    return v1::AlignSet::NewStub(
        grpc::CreateCustomChannel(server_->address(), grpc::InsecureChannelCredentials(), args));
  }
  ServiceMetrics Metrics() {
    auto m = Client()->GetMetrics();
    EXPECT_TRUE(m.ok()) << m.status().message();
    return m.ok() ? *m : ServiceMetrics{};
  }

  TempDir dir_;
  std::unique_ptr<ServerProcess> server_;
};

TEST_F(E2eTest, HealthServiceReportsServing) {
  StartServer(kFast);
  grpc::health::v1::HealthCheckRequest req;
  grpc::health::v1::HealthCheckResponse resp;
  grpc::ClientContext ctx;
  auto stub = grpc::health::v1::Health::NewStub(
      grpc::CreateChannel(server_->address(), grpc::InsecureChannelCredentials()));
  ASSERT_TRUE(stub->Check(&ctx, req, &resp).ok());
  EXPECT_EQ(resp.status(), grpc::health::v1::HealthCheckResponse::SERVING);
  auto healthy = Client()->Healthy();
  ASSERT_TRUE(healthy.ok()) << healthy.status().message();
  EXPECT_TRUE(*healthy);
}

TEST_F(E2eTest, MissThenHitReturnsIdenticalBytesAndAlignmentIsExact) {
  StartServer(kFast);
  auto client = Client();
  auto miss = client->GetAlignedSet(128, {30.0});
  ASSERT_TRUE(miss.ok()) << miss.status().message();
  EXPECT_FALSE(miss->info.from_cache);
  EXPECT_EQ(miss->points.size(), 128u);
  EXPECT_EQ(miss->raw.size(), 128u * 16);
  EXPECT_EQ(miss->info.phi1, 30);
  EXPECT_EQ(miss->info.iterations, 60);
  EXPECT_EQ(miss->info.max_iterations, 60);
  EXPECT_GT(miss->info.optimize_seconds, 0.0);
  EXPECT_FALSE(miss->info.profile.empty());
  // The optimizer made progress from its Owen-Sobol start (white noise: 1).
  EXPECT_LT(miss->info.loss_spectrum, 1.0);

  auto hit = client->GetAlignedSet(128, {30.0});
  ASSERT_TRUE(hit.ok()) << hit.status().message();
  EXPECT_TRUE(hit->info.from_cache);
  EXPECT_EQ(hit->raw, miss->raw);
  EXPECT_EQ(hit->info.loss_total, miss->info.loss_total);

  // 60° is the same canonical set, swapped: (x, y) -> (y, x), bit for bit.
  auto swapped = client->GetAlignedSet(128, {60.0});
  ASSERT_TRUE(swapped.ok()) << swapped.status().message();
  EXPECT_TRUE(swapped->info.from_cache);
  EXPECT_TRUE(swapped->info.swapped);
  EXPECT_FALSE(swapped->info.inverted);
  ASSERT_EQ(swapped->info.served_deg, std::vector<int>{60});
  for (size_t i = 0; i < 128; ++i) {
    EXPECT_EQ(swapped->points[i].x, miss->points[i].y);
    EXPECT_EQ(swapped->points[i].y, miss->points[i].x);
  }
  const auto m = Metrics();
  EXPECT_EQ(m.optimizations_started, 1u);
  EXPECT_EQ(m.cache_misses, 1u);
  EXPECT_EQ(m.cache_hits_memory, 2u);
}

TEST_F(E2eTest, ThirtyTwoConcurrentRequestsRunExactlyOneOptimization) {
  // Long enough (N = 512, 200 iterations) that the requests overlap it.
  StartServer({"--max-iterations", "200", "--workers", "2", "--threads-per-worker", "1"});
  constexpr int kClients = 32;
  std::vector<StatusOr<AlignedSet>> results(kClients, Status::Internal("not run"));
  std::atomic<int> ready{0};
  std::vector<std::thread> threads;
  for (int i = 0; i < kClients; ++i) {
    threads.emplace_back([&, i] {
      ConnectOptions o;
      o.separate_connection = true;
      auto c = Client(o);
      ++ready;
      while (ready.load() < kClients) std::this_thread::yield();
      results[i] = c->GetAlignedSet(512, {i % 2 ? 100.0 : 10.0});  // one canonical key
    });
  }
  for (auto& t : threads) t.join();
  ASSERT_TRUE(results[0].ok()) << results[0].status().message();
  int swapped = 0;
  for (const auto& r : results) {
    ASSERT_TRUE(r.ok()) << r.status().message();
    EXPECT_EQ(r->info.phi1, 10);
    EXPECT_EQ(r->info.loss_total, results[0]->info.loss_total);
    swapped += r->info.swapped;
    if (r->info.swapped == results[0]->info.swapped) EXPECT_EQ(r->raw, results[0]->raw);
  }
  EXPECT_EQ(swapped, kClients / 2);
  const auto m = Metrics();
  EXPECT_EQ(m.optimizations_started, 1u);
  EXPECT_EQ(m.optimizations_completed, 1u);
  EXPECT_EQ(m.cache_misses + m.cache_hits_memory + m.cache_hits_db, static_cast<uint64_t>(kClients));
  EXPECT_GT(m.shared_waits, 0u);  // they did overlap
}

TEST_F(E2eTest, AStoppingServerFinishesTheCallsInFlightAndDoesNotWaitForIdleClients) {
  // gRPC's shutdown also waits for the clients' connections to close, and a
  // C++ client keeps an idle one open: before the server closed them once
  // its calls were done, this server took its whole grace (60 s) to stop;
  // and then up to 10 s more at exit in gRPC's own teardown.
  // The call in flight is a large pmj02bn set (seconds to make; running
  // optimizations are not what the grace is for: they end at their next
  // time slice with UNAVAILABLE, for the client to retry elsewhere).
  StartServer(With(kFast, {"--shutdown-grace", "60", "--max-n", "262144", "--log-level", "debug"}));
  auto idle = Client();
  ASSERT_TRUE(idle->GetAlignedSet(64, {30.0}).ok());
  ConnectOptions separate;
  separate.separate_connection = true;
  auto busy = Client(separate);
  ASSERT_TRUE(busy->GetAlignedSet(64, {30.0}).ok());  // connected: the call below goes out at once
  StatusOr<PointSet> running = Status::Internal("not run");
  const auto sent = std::chrono::steady_clock::now();
  std::thread call([&] { running = busy->GetSamples("pmj02bn", 262144, 1, std::nullopt); });
  // The server has the call (its debug line) when SIGTERM comes.
  EXPECT_TRUE(server_->WaitForLog({"N=262144"}, 1, std::chrono::seconds(20)));
  const int code = server_->Stop(SIGTERM);
  const double stopped = std::chrono::duration<double>(std::chrono::steady_clock::now() - sent).count();
  call.join();
  EXPECT_EQ(code, 0);
  ASSERT_TRUE(running.ok()) << running.status().message();  // given its grace
  EXPECT_EQ(running->size(), 262144u);
  // Well under the grace, and under the 10 s poll gRPC's teardown at exit
  // could add (alignset-server's main).
  EXPECT_LT(stopped, 10.0);
}

TEST_F(E2eTest, ACallSentWhileTheServerRestartsWaitsForItAndIsServed) {
  StartServer(With(kFast, {"--shutdown-grace", "1"}));
  ConnectOptions o;
  o.connect_timeout_seconds = 20;  // a loaded machine may take seconds to restart it
  auto client = Client(o);
  auto first = client->GetAlignedSet(64, {30.0});
  ASSERT_TRUE(first.ok()) << first.status().message();
  const std::string port = std::to_string(server_->port());
  server_->Stop(SIGTERM);
  server_.reset();
  // The server is down when the call goes out and listens on the same port
  // (same database) a moment later: before the connection wait, the call
  // failed UNAVAILABLE within its 0.7 s of retries.
  std::unique_ptr<ServerProcess> restarted;
  std::thread restart([&] {
    std::this_thread::sleep_for(700ms);  // the down time itself, not a wait for the server
    restarted = std::make_unique<ServerProcess>(dir_.path(), With(kFast, {"--listen", "127.0.0.1:" + port}));
  });
  const auto sent = std::chrono::steady_clock::now();
  auto again = client->GetAlignedSet(64, {30.0});
  const double waited = std::chrono::duration<double>(std::chrono::steady_clock::now() - sent).count();
  restart.join();
  server_ = std::move(restarted);
  ASSERT_EQ(server_->error(), "");
  ASSERT_TRUE(again.ok()) << again.status().message();
  EXPECT_GE(waited, 0.7);  // it was answered by the restarted server
  EXPECT_TRUE(again->info.from_cache);  // from the database the first server wrote
  EXPECT_EQ(again->raw, first->raw);
}

TEST_F(E2eTest, ANegativeNonFiniteOrOverlongTimeoutIsRefused) {
  // 1e12 s from now is past what the clock's nanoseconds hold: refused, not
  // wrapped into a deadline in the past.
  for (double t : {-1.0, std::nan(""), std::numeric_limits<double>::infinity(), 1e12}) {
    for (double ConnectOptions::*field :
         {&ConnectOptions::connect_timeout_seconds, &ConnectOptions::timeout_seconds}) {
      ConnectOptions o;
      o.address = "127.0.0.1:1";
      o.*field = t;
      auto c = ServiceClient::Connect(o);
      ASSERT_FALSE(c.ok()) << t;
      EXPECT_EQ(c.status().code(), Status::Code::kInvalidArgument);
      EXPECT_NE(c.status().message().find("timeout must be"), std::string::npos);
    }
  }
  // Per call: refused before anything is sent (nothing listens on port 1),
  // unary and streaming alike; the limit itself is a valid timeout.
  ConnectOptions o;
  o.address = "127.0.0.1:1";
  o.connect_timeout_seconds = 0;
  auto c = ServiceClient::Connect(o);
  ASSERT_TRUE(c.ok()) << c.status().message();
  for (double t : {-1.0, std::nan(""), 1e12}) {
    CallOptions call;
    call.timeout_seconds = t;
    auto got = (*c)->GetAlignedSet(SetRequest{64, {30.0}, 0}, call);
    ASSERT_FALSE(got.ok()) << t;
    EXPECT_EQ(got.status().code(), Status::Code::kInvalidArgument) << got.status().message();
    EXPECT_NE(got.status().message().find("call timeout"), std::string::npos);
    auto watched = (*c)->WatchAlignedSet(SetRequest{64, {30.0}, 0}, {}, call);
    ASSERT_FALSE(watched.ok()) << t;
    EXPECT_EQ(watched.status().code(), Status::Code::kInvalidArgument);
  }
  CallOptions longest;
  longest.timeout_seconds = 1e9;
  auto got = (*c)->GetAlignedSet(SetRequest{64, {30.0}, 0}, longest);
  ASSERT_FALSE(got.ok());
  EXPECT_EQ(got.status().code(), Status::Code::kUnavailable) << got.status().message();
}

void ExpectStatus(const grpc::Status& s, grpc::StatusCode code, const std::string& fragment) {
  EXPECT_EQ(s.error_code(), code) << s.error_message();
  EXPECT_NE(s.error_message().find(fragment), std::string::npos) << s.error_message();
}

TEST_F(E2eTest, BadRequestsGetInvalidArgumentAndTheServerKeepsServing) {
  StartServer(kFast);
  auto stub = RawStub();
  auto get = [&](uint32_t n, std::vector<double> dirs) {
    v1::AlignedSetRequest req;
    req.set_n(n);
    for (double d : dirs) req.add_directions_deg(d);
    v1::AlignedSetResponse resp;
    grpc::ClientContext ctx;
    return stub->GetAlignedSet(&ctx, req, &resp);
  };
  using C = grpc::StatusCode;
  ExpectStatus(get(0, {30}), C::INVALID_ARGUMENT, "N = 0 is below the minimum of 16 points (missing?)");
  ExpectStatus(get(8, {30}), C::INVALID_ARGUMENT, "below the minimum of 16");
  ExpectStatus(get(4097, {30}), C::INVALID_ARGUMENT, "maximum of 4096");
  ExpectStatus(get(64, {std::nan("")}), C::INVALID_ARGUMENT, "not a finite number");
  ExpectStatus(get(64, {-INFINITY}), C::INVALID_ARGUMENT, "not a finite number");
  ExpectStatus(get(64, {10, 20, 30}), C::INVALID_ARGUMENT, "one or two directions");
  ExpectStatus(get(64, {10, 20, 30}), C::INVALID_ARGUMENT, "made locally: alignset optimize");
  ExpectStatus(get(64, {}), C::INVALID_ARGUMENT, "one or two directions");

  v1::SamplesRequest sreq;
  sreq.set_sampler("no-such-sampler");
  sreq.set_n(64);
  v1::SamplesResponse sresp;
  grpc::ClientContext sctx;
  ExpectStatus(stub->GetSamples(&sctx, sreq, &sresp), C::INVALID_ARGUMENT,
               "unknown sampler 'no-such-sampler'");

  // 2 MiB of directions: over the server's 1 MiB receive limit.
  std::vector<double> huge(1 << 18, 1.0);
  ExpectStatus(get(64, huge), C::RESOURCE_EXHAUSTED, "");

  v1::PrecomputeRequest preq;
  preq.add_n(64);
  preq.set_space(v1::ONE_DIRECTION);
  preq.set_shard_index(3);
  preq.set_shard_count(3);
  grpc::ClientContext pctx;
  auto reader = stub->Precompute(&pctx, preq);
  v1::PrecomputeProgress p;
  while (reader->Read(&p)) {
  }
  ExpectStatus(reader->Finish(), C::INVALID_ARGUMENT, "shard index 3");

  // Still serving, and counting what it refused.
  auto ok = Client()->GetAlignedSet(64, {45.0});
  ASSERT_TRUE(ok.ok()) << ok.status().message();
  EXPECT_EQ(ok->points.size(), 64u);
  EXPECT_EQ(Metrics().requests_invalid, 10u);
}

int64_t CountRows(const std::string& db) {
  auto cache = storage::SetCache::Open(db, {.read_only = true});
  EXPECT_TRUE(cache.ok()) << cache.status().message();
  auto stats = (*cache)->Stats();
  return stats.ok() ? stats->sets : -1;
}

std::string IntegrityCheck(const std::string& db) {
  sqlite3* h = nullptr;
  std::string result = "open failed";
  if (sqlite3_open_v2(db.c_str(), &h, SQLITE_OPEN_READWRITE, nullptr) == SQLITE_OK) {
    sqlite3_stmt* st = nullptr;
    sqlite3_prepare_v2(h, "PRAGMA integrity_check", -1, &st, nullptr);
    result.clear();
    while (sqlite3_step(st) == SQLITE_ROW) {
      result += reinterpret_cast<const char*>(sqlite3_column_text(st, 0));
    }
    sqlite3_finalize(st);
  }
  sqlite3_close(h);
  return result;
}

TEST_F(E2eTest, SigkillDuringPrecomputeLeavesAnIntactDatabaseAndTheRerunResumes) {
  const auto flags = With(kFast, {"--max-iterations", "100"});
  StartServer(flags);
  PrecomputeSpec spec;
  spec.n = {128};
  spec.space = 1;  // the 46 one-direction keys
  const pid_t pid = server_->pid();
  std::atomic<bool> killed{false};
  auto first = Client()->Precompute(spec, [&](const PrecomputeUpdate& u) {
    if (u.done >= 3 && !killed.exchange(true)) kill(pid, SIGKILL);
  });
  ASSERT_TRUE(killed.load());
  EXPECT_FALSE(first.ok());  // the stream broke
  server_->Stop(SIGKILL);    // reap

  EXPECT_EQ(IntegrityCheck(server_->db_path()), "ok");
  const int64_t stored = CountRows(server_->db_path());
  EXPECT_GE(stored, 3);
  EXPECT_LT(stored, 46);
  {
    auto cache = storage::SetCache::Open(server_->db_path());
    ASSERT_TRUE(cache.ok()) << cache.status().message();
    auto verify = (*cache)->Verify();
    ASSERT_TRUE(verify.ok()) << verify.status().message();
    EXPECT_EQ(verify->checked, stored);
    EXPECT_TRUE(verify->corrupt.empty());
  }

  StartServer(flags);
  auto second = Client()->Precompute(spec, nullptr);
  ASSERT_TRUE(second.ok()) << second.status().message();
  EXPECT_EQ(second->total, 46u);
  EXPECT_EQ(second->cached_already, static_cast<uint64_t>(stored));
  EXPECT_EQ(second->done, static_cast<uint64_t>(46 - stored));
  EXPECT_EQ(second->failed, 0u);
  EXPECT_EQ(second->remaining, 0u);
  EXPECT_EQ(Metrics().optimizations_started, static_cast<uint64_t>(46 - stored));
  EXPECT_EQ(CountRows(server_->db_path()), 46);
}

// Flips one byte in the middle of every stored point blob.
int FlipBlobBytes(const std::string& db) {
  sqlite3* h = nullptr;
  if (sqlite3_open_v2(db.c_str(), &h, SQLITE_OPEN_READWRITE, nullptr) != SQLITE_OK) return -1;
  sqlite3_stmt* st = nullptr;
  sqlite3_prepare_v2(h, "SELECT rowid, points FROM sets", -1, &st, nullptr);
  std::vector<std::pair<int64_t, std::string>> rows;
  while (sqlite3_step(st) == SQLITE_ROW) {
    const char* b = static_cast<const char*>(sqlite3_column_blob(st, 1));
    rows.emplace_back(sqlite3_column_int64(st, 0), std::string(b, sqlite3_column_bytes(st, 1)));
  }
  sqlite3_finalize(st);
  for (auto& [rowid, blob] : rows) {
    blob[blob.size() / 2] ^= 0x01;
    sqlite3_prepare_v2(h, "UPDATE sets SET points = ? WHERE rowid = ?", -1, &st, nullptr);
    sqlite3_bind_blob(st, 1, blob.data(), static_cast<int>(blob.size()), SQLITE_TRANSIENT);
    sqlite3_bind_int64(st, 2, rowid);
    if (sqlite3_step(st) != SQLITE_DONE) rows.clear();
    sqlite3_finalize(st);
  }
  sqlite3_close(h);
  return static_cast<int>(rows.size());
}

TEST_F(E2eTest, FlippedByteInAStoredBlobIsDetectedAndTheSetRecomputed) {
  StartServer(kFast);
  auto original = Client()->GetAlignedSet(128, {20.0, 70.0});
  ASSERT_TRUE(original.ok()) << original.status().message();
  EXPECT_EQ(original->info.direction_count, 2);
  server_->Stop(SIGTERM);
  ASSERT_EQ(FlipBlobBytes(server_->db_path()), 1);

  StartServer(kFast);
  auto again = Client()->GetAlignedSet(128, {20.0, 70.0});
  ASSERT_TRUE(again.ok()) << again.status().message();
  EXPECT_FALSE(again->info.from_cache);  // recomputed, not served corrupt
  EXPECT_EQ(again->raw, original->raw);  // the optimizer is deterministic
  auto m = Metrics();
  EXPECT_EQ(m.corrupt_rows, 1u);
  EXPECT_EQ(m.optimizations_started, 1u);
  server_->Stop(SIGTERM);
  auto cache = storage::SetCache::Open(server_->db_path());
  ASSERT_TRUE(cache.ok());
  auto verify = (*cache)->Verify();
  ASSERT_TRUE(verify.ok());
  EXPECT_EQ(verify->checked, 1);
  EXPECT_TRUE(verify->corrupt.empty());  // the row was replaced
}

TEST_F(E2eTest, PrecomputeRerunRecomputesACorruptRowInsteadOfCountingItCached) {
  const auto flags = With(kFast, {"--max-iterations", "100"});
  StartServer(flags);
  PrecomputeSpec spec;
  spec.n = {64};
  spec.space = 1;
  auto first = Client()->Precompute(spec, nullptr);
  ASSERT_TRUE(first.ok()) << first.status().message();
  EXPECT_EQ(first->done, 46u);
  server_->Stop(SIGTERM);
  ASSERT_EQ(FlipBlobBytes(server_->db_path()), 46);  // every row corrupt

  StartServer(flags);
  auto second = Client()->Precompute(spec, nullptr);
  ASSERT_TRUE(second.ok()) << second.status().message();
  EXPECT_EQ(second->cached_already, 0u);
  EXPECT_EQ(second->done, 46u);
  EXPECT_EQ(Metrics().corrupt_rows, 46u);
  server_->Stop(SIGTERM);
  auto cache = storage::SetCache::Open(server_->db_path());
  ASSERT_TRUE(cache.ok());
  auto verify = (*cache)->Verify();
  ASSERT_TRUE(verify.ok());
  EXPECT_EQ(verify->checked, 46);
  EXPECT_TRUE(verify->corrupt.empty());
}

TEST_F(E2eTest, WrongOrMissingTokenIsRefusedWhenAuthenticationIsOn) {
  const std::string token_file = dir_.path() + "/token";
  std::ofstream(token_file) << "s3cret-token\n";
  StartServer(With(kFast, {"--token-file", token_file}));
  auto none = Client()->GetAlignedSet(64, {30.0});
  ASSERT_FALSE(none.ok());
  EXPECT_NE(none.status().message().find("UNAUTHENTICATED"), std::string::npos)
      << none.status().message();
  ConnectOptions wrong;
  wrong.token = "guess";
  auto bad = Client(wrong)->GetMetrics();
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(bad.status().message().find("UNAUTHENTICATED: invalid bearer token"), std::string::npos)
      << bad.status().message();
  ConnectOptions right;
  right.token = "s3cret-token";
  auto good = Client(right)->GetAlignedSet(64, {30.0});
  ASSERT_TRUE(good.ok()) << good.status().message();
  // The health service stays open for probes.
  auto healthy = Client()->Healthy();
  ASSERT_TRUE(healthy.ok()) << healthy.status().message();
  EXPECT_TRUE(*healthy);
}

TEST_F(E2eTest, DeadlineStopsTheWaitAndTheAbandonedOptimizationIsCancelled) {
  StartServer({"--max-iterations", "100000", "--workers", "1", "--threads-per-worker", "1", "--log-level", "info"});
  ConnectOptions o;
  o.timeout_seconds = 0.3;
  auto r = Client(o)->GetAlignedSet(2048, {7.0});
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().code(), Status::Code::kDeadlineExceeded) << r.status().message();
  // Nobody else wanted the set: the optimization is stopped, nothing stored.
  // Its worker's line comes after the count.
  EXPECT_TRUE(server_->WaitForLog({"optimize cancelled", "withdrawn"}, 1, std::chrono::seconds(10)));
  const ServiceMetrics m = Metrics();
  EXPECT_EQ(m.optimizations_cancelled, 1u);
  EXPECT_EQ(m.optimizations_completed, 0u);
  EXPECT_EQ(m.running, 0u);
  auto stats = Client()->GetCacheStats();
  ASSERT_TRUE(stats.ok());
  EXPECT_EQ(stats->sets, 0);
}

TEST_F(E2eTest, WatchStreamsProgressThenTheSet) {
  // Long enough to be watched on a fast machine (about 0.9 s here): the
  // stream looks every 100 ms, and a job that runs from one look to the
  // next shows only its queue position and then the set (100 iterations at
  // N = 1024 did, in CI).
  StartServer({"--max-iterations", "1000", "--workers", "1", "--threads-per-worker", "1"});
  int progress_events = 0;
  int last_iteration = -1;
  bool monotone = true;
  auto set = Client()->WatchAlignedSet(2048, {33.0}, [&](const WatchUpdate& u) {
    if (u.queued) return;
    ++progress_events;
    monotone = monotone && u.iteration >= last_iteration;
    last_iteration = u.iteration;
  });
  ASSERT_TRUE(set.ok()) << set.status().message();
  EXPECT_EQ(set->points.size(), 2048u);
  EXPECT_GT(progress_events, 0);
  EXPECT_TRUE(monotone);
}

TEST_F(E2eTest, TlsServerServesATrustingClient) {
  const std::string d = dir_.path();
  auto gen = RunCommand("openssl req -x509 -newkey ec -pkeyopt ec_paramgen_curve:prime256v1 -nodes "
                        "-days 1 -subj /CN=localhost -addext subjectAltName=DNS:localhost -keyout " +
                        d + "/key.pem -out " + d + "/cert.pem");
  ASSERT_EQ(gen.exit_code, 0) << gen.output;
  StartServer(With(kFast, {"--tls-cert", d + "/cert.pem", "--tls-key", d + "/key.pem"}));
  ConnectOptions o;
  o.tls_ca_file = d + "/cert.pem";
  o.tls_server_name = "localhost";
  auto set = Client(o)->GetAlignedSet(64, {12.0});
  ASSERT_TRUE(set.ok()) << set.status().message();
  auto plain = Client()->GetAlignedSet(64, {12.0});  // plaintext to a TLS port
  EXPECT_FALSE(plain.ok());
}

TEST_F(E2eTest, GetSamplesServesTheCoreSamplersOptionallySheared) {
  StartServer(kFast);
  auto client = Client();
  auto plain = client->GetSamples("pmj02bn", 256, 7, std::nullopt);
  ASSERT_TRUE(plain.ok()) << plain.status().message();
  ASSERT_EQ(plain->size(), 256u);
  auto sheared = client->GetSamples("pmj02bn", 256, 7, 30.0);
  ASSERT_TRUE(sheared.ok()) << sheared.status().message();
  ASSERT_EQ(sheared->size(), 256u);
  // Algorithm 2 at 30°: p = (tan 30°, 0), x' = x - p.x * y (mod 1), y kept.
  const double t = std::tan(30.0 * M_PI / 180.0);
  for (size_t i = 0; i < 256; ++i) {
    EXPECT_EQ((*sheared)[i].y, (*plain)[i].y);
    double d = std::fabs((*sheared)[i].x - ((*plain)[i].x - t * (*plain)[i].y));
    d = std::fabs(d - std::round(d));  // equal mod 1
    EXPECT_LT(d, 1e-12) << i;
  }
  // A sampler that needs a square N says so.
  auto refused = client->GetSamples("jittered", 250, 1, std::nullopt);
  ASSERT_FALSE(refused.ok());
  EXPECT_NE(refused.status().message().find("INVALID_ARGUMENT"), std::string::npos);
}

TEST_F(E2eTest, CliGetWritesTheSetAndFailsWithOneLine) {
  StartServer(kFast);
  const std::string out = dir_.path() + "/set.txt";
  const std::string cli = std::string(ALIGNSET_CLI_PATH) + " ";
  auto ok = RunCommand(cli + "get --server " + server_->address() + " --n 64 --dir 30 --dir 100 --quiet --out " + out);
  ASSERT_EQ(ok.exit_code, 0) << ok.output;
  std::ifstream in(out);
  int points = 0;
  for (std::string line; std::getline(in, line);) points += !line.empty() && line[0] != '#';
  EXPECT_EQ(points, 64);
  auto npy = RunCommand(cli + "get --server " + server_->address() + " --n 64 --dir 30 --dir 100 --quiet --out " + out + ".npy");
  ASSERT_EQ(npy.exit_code, 0) << npy.output;
  EXPECT_NE(npy.output.find("from cache     yes"), std::string::npos) << npy.output;

  auto bad = RunCommand(cli + "get --server " + server_->address() + " --n 5000 --dir 30 --out " + out);
  EXPECT_NE(bad.exit_code, 0);
  EXPECT_EQ(std::count(bad.output.begin(), bad.output.end(), '\n'), 1) << bad.output;
  EXPECT_NE(bad.output.find("INVALID_ARGUMENT"), std::string::npos) << bad.output;

  auto stats = RunCommand(cli + "stats --server " + server_->address());
  ASSERT_EQ(stats.exit_code, 0) << stats.output;
  EXPECT_NE(stats.output.find("sets              1 (0 one-direction, 1 two-direction)"), std::string::npos)
      << stats.output;

  server_->Stop(SIGTERM);
  auto down = RunCommand(cli + "get --server " + server_->address() + " --n 64 --dir 30 --out " + out);
  EXPECT_NE(down.exit_code, 0);
  EXPECT_NE(down.output.find("UNAVAILABLE"), std::string::npos) << down.output;
}

}  // namespace
}  // namespace alignset::e2e

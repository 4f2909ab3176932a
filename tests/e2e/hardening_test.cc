// End-to-end checks for the failures an outside probe found (issue 16) and
// the per-service health check (issue 15): each against the real server on
// loopback, through raw stubs of the wire contract.
#include <google/protobuf/descriptor.pb.h>
#include <gtest/gtest.h>
#include <signal.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <map>
#include <thread>

#include "alignset/v1/alignset.grpc.pb.h"
#include "grpc/health/v1/health.grpc.pb.h"
#include "grpc/reflection/v1alpha/reflection.grpc.pb.h"
#include "storage/set_cache.h"
#include "storage/set_rows.h"
#include "storage/sqlite_handle.h"
#include "tests/damage_pages.h"
#include "tests/e2e/e2e_util.h"
#include "tests/e2e/server_process.h"

namespace alignset::e2e {
namespace {

using namespace std::chrono_literals;
using Clock = std::chrono::steady_clock;

const std::vector<std::string> kFast = {"--max-iterations", "60", "--workers", "1",
                                        "--threads-per-worker", "1", "--max-n", "4096"};

std::vector<std::string> With(std::vector<std::string> a, const std::vector<std::string>& b) {
  a.insert(a.end(), b.begin(), b.end());
  return a;
}

class HardeningTest : public ::testing::Test {
 protected:
  void StartServer(const std::vector<std::string>& flags) {
    server_.reset();
    server_ = std::make_unique<ServerProcess>(dir_.path(), flags);
    ASSERT_EQ(server_->error(), "");
  }
  std::string Log() const { return ReadText(dir_.path() + "/server.log"); }

  TempDir dir_;
  std::unique_ptr<ServerProcess> server_;
};

// ------------------------------------------------------------- item 2

TEST_F(HardeningTest, SecondServerOnTheSameAddressFailsToStartWithAClearMessage) {
  StartServer(kFast);
  TempDir other;
  ServerProcess second(other.path(), With(kFast, {"--listen", server_->address()}));
  ASSERT_NE(second.error(), "") << "a second server started on " << server_->address();
  EXPECT_NE(second.error().find("already in use"), std::string::npos) << second.error();
  // The first one still serves every call, from its own database.
  for (int i = 0; i < 10; ++i) {
    EXPECT_EQ(GetMetrics(server_->address()).requests_get(), 0u);
  }
}

TEST_F(HardeningTest, OutOfRangeOrMissingPortIsRefused) {
  const std::string base = "timeout 10 " + ServerBinary() + " --db " + dir_.path() + "/x.sqlite --listen ";
  for (std::string listen : {"127.0.0.1:80000", "127.0.0.1:65536", "127.0.0.1:-1", "127.0.0.1"}) {
    auto r = RunCommand(base + listen);
    EXPECT_EQ(r.exit_code, 2) << listen << ": " << r.output;
    EXPECT_NE(r.output.find("--listen"), std::string::npos) << r.output;
  }
  auto r = RunCommand(base + "127.0.0.1:80000");
  EXPECT_NE(r.output.find("outside 0..65535"), std::string::npos) << r.output;
}

TEST_F(HardeningTest, PortZeroServesOnlyTheReportedPort) {
  StartServer(kFast);
  EXPECT_EQ(ListeningPorts(server_->pid()), std::set<int>{server_->port()});
}

// ------------------------------------------------------------- health

TEST_F(HardeningTest, HealthAnswersForTheAlignSetServiceByName) {
  StartServer(kFast);
  auto stub = grpc::health::v1::Health::NewStub(OwnChannel(server_->address()));
  auto check = [&](const std::string& service, grpc::health::v1::HealthCheckResponse* resp) {
    grpc::health::v1::HealthCheckRequest req;
    req.set_service(service);
    grpc::ClientContext ctx;
    return stub->Check(&ctx, req, resp);
  };
  for (std::string name : {"alignset.v1.AlignSet", ""}) {
    grpc::health::v1::HealthCheckResponse resp;
    grpc::Status s = check(name, &resp);
    ASSERT_TRUE(s.ok()) << "'" << name << "': " << s.error_message();
    EXPECT_EQ(resp.status(), grpc::health::v1::HealthCheckResponse::SERVING) << name;
  }
  grpc::health::v1::HealthCheckResponse resp;
  EXPECT_EQ(check("no.such.Service", &resp).error_code(), grpc::StatusCode::NOT_FOUND);
}

// ------------------------------------------------------------- item 5

TEST_F(HardeningTest, WatchSendsSomethingAtLeastOnceASecondAtLargeN) {
  // One thread at N = 65536: the optimizer's progress callbacks come
  // hundreds of milliseconds apart, which is where progress got lost.
  StartServer({"--workers", "1", "--threads-per-worker", "1"});
  auto stub = OwnStub(server_->address());
  grpc::ClientContext ctx;
  auto reader = stub->WatchAlignedSet(&ctx, SetRequest(65536, {21.0}));
  const auto t0 = Clock::now();
  std::vector<double> at;  // seconds since the call, one per event
  int progress = 0;
  v1::WatchEvent ev;
  while (Clock::now() - t0 < 4s && reader->Read(&ev)) {
    at.push_back(std::chrono::duration<double>(Clock::now() - t0).count());
    progress += ev.has_progress();
  }
  ctx.TryCancel();
  while (reader->Read(&ev)) {
  }
  reader->Finish();
  ASSERT_FALSE(at.empty());
  double gap = at.front();
  for (size_t i = 1; i < at.size(); ++i) gap = std::max(gap, at[i] - at[i - 1]);
  gap = std::max(gap, 4.0 - at.back());
  // Once a second, with half a second for a loaded CI machine.
  EXPECT_LE(gap, 1.5) << at.size() << " events in 4 s";
  EXPECT_GE(progress, 3);
}

// ------------------------------------------------------------- item 6

TEST_F(HardeningTest, ClientStringsAreCutAndEscapedInErrorsAndLogs) {
  StartServer(With(kFast, {"--log-level", "info"}));
  auto stub = OwnStub(server_->address());
  auto samples = [&](const std::string& name) {
    v1::SamplesRequest req;
    req.set_sampler(name);
    req.set_n(64);
    v1::SamplesResponse resp;
    grpc::ClientContext ctx;
    return stub->GetSamples(&ctx, req, &resp);
  };
  const std::string forged = "2099-01-01T00:00:00.000 error forged line";
  grpc::Status s = samples("x\n" + forged);
  EXPECT_EQ(s.error_code(), grpc::StatusCode::INVALID_ARGUMENT) << s.error_message();
  EXPECT_NE(s.error_message().find("'x\\n2099"), std::string::npos) << s.error_message();
  s = samples(std::string(100 * 1024, 'n'));
  EXPECT_EQ(s.error_code(), grpc::StatusCode::INVALID_ARGUMENT) << s.error_message().substr(0, 200);
  EXPECT_LT(s.error_message().size(), 512u);
  EXPECT_NE(s.error_message().find("(102400 bytes)"), std::string::npos) << s.error_message().substr(0, 200);

  const size_t log_before = Log().size();
  for (int i = 0; i < 20; ++i) {
    s = samples(std::string(1000 * 1000, 'm'));
    EXPECT_EQ(s.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
    EXPECT_LT(s.error_message().size(), 512u);
  }
  EXPECT_LT(Log().size() - log_before, 20u * 1024) << "20 one-megabyte names grew the log";
  const std::string log = Log();
  EXPECT_EQ(log.find("\n" + forged), std::string::npos) << "a client forged a log line";
  // The refusals were logged, escaped.
  EXPECT_NE(log.find("'x\\n2099"), std::string::npos);
  // And the server kept serving.
  EXPECT_TRUE(samples("pmj02bn").ok());
}

// ------------------------------------------------------------- item 7

// Marks the file as written by a newer SQLite format that this one may read
// but not write (header byte 18, the write version, > 2). SQLite then opens
// it read-only whatever the file permissions, so the test also holds as root.
void MakeReadOnlyFormat(const std::string& db) {
  std::fstream f(db, std::ios::in | std::ios::out | std::ios::binary);
  f.seekp(18);
  f.put(3);
}

TEST_F(HardeningTest, SetServedButNotStoredIsReportedInTheResponseMetricsAndLog) {
  StartServer(kFast);
  {
    auto stub = OwnStub(server_->address());
    grpc::ClientContext ctx;
    v1::AlignedSetResponse resp;
    ASSERT_TRUE(stub->GetAlignedSet(&ctx, SetRequest(64, {10.0}), &resp).ok());
    EXPECT_FALSE(resp.metadata().not_stored());
  }
  server_->Stop(SIGTERM);
  MakeReadOnlyFormat(server_->db_path());
  StartServer(kFast);
  EXPECT_NE(Log().find("is not writable"), std::string::npos) << Log();
  auto stub = OwnStub(server_->address());
  for (int round = 0; round < 2; ++round) {  // optimized, then from memory
    grpc::ClientContext ctx;
    v1::AlignedSetResponse resp;
    grpc::Status s = stub->GetAlignedSet(&ctx, SetRequest(64, {20.0}), &resp);
    ASSERT_TRUE(s.ok()) << s.error_message();
    EXPECT_EQ(resp.metadata().from_cache(), round == 1);
    EXPECT_TRUE(resp.metadata().not_stored()) << round;
  }
  grpc::ClientContext ctx;
  v1::AlignedSetResponse stored;
  ASSERT_TRUE(stub->GetAlignedSet(&ctx, SetRequest(64, {10.0}), &stored).ok());
  EXPECT_FALSE(stored.metadata().not_stored());  // read back from the file
  EXPECT_EQ(GetMetrics(server_->address()).sets_not_stored(), 1u);
}

// ------------------------------------------------------------- item 4

TEST_F(HardeningTest, DamagedPagesAreReportedListedByVerifyAndRecovered) {
  StartServer(kFast);
  PrecomputeOneDirection(server_->address());
  server_->Stop(SIGTERM);  // checkpointed: no WAL left
  const std::string db = server_->db_path();

  std::map<int64_t, storage::SetKey> keys;
  {
    auto raw = storage::Db::Open(db, SQLITE_OPEN_READONLY, 1000);
    ASSERT_TRUE(raw.ok());
    auto stmt = storage::Stmt::Prepare(raw->get(), std::string("SELECT ") + storage::kKeyColumns +
                                                       ", rowid FROM sets");
    ASSERT_TRUE(stmt.ok());
    while (*stmt->Step()) keys[stmt->Int(6)] = storage::KeyFromRow(*stmt);
  }
  ASSERT_EQ(keys.size(), 46u);
  const auto pages = ::alignset::testing::FindTablePages(db, "sets");
  ASSERT_GT(pages.leaves.size(), 2u);
  const size_t victim = pages.leaves.size() / 2;
  ::alignset::testing::DamagePageHeader(db, pages.page_size, pages.leaves[victim]);
  std::set<std::string> lost;
  for (int64_t rowid : pages.rowids[victim]) lost.insert(storage::KeyToString(keys.at(rowid)));
  ASSERT_FALSE(lost.empty());

  // Reported: an error line naming the repair, and the metric.
  StartServer(With(kFast, {"--metrics-listen", "127.0.0.1:0"}));
  // The check runs in the background; its error line comes after the metric.
  EXPECT_TRUE(server_->WaitForLog({"is damaged: quick_check"}, 1, 20s)) << Log();
  EXPECT_GT(GetMetrics(server_->address()).database_integrity_errors(), 0u);
  EXPECT_NE(Log().find("is damaged: quick_check"), std::string::npos) << Log();
  EXPECT_NE(Log().find("alignset cache recover"), std::string::npos) << Log();
  const auto scraped = ParsePrometheus(HttpRequest(server_->metrics_port(), "GET", "/metrics").body);
  EXPECT_GT(scraped.at("alignset_database_integrity_errors"), 0.0);
  // Stats count what can be read instead of failing with DATA_LOSS.
  {
    auto stub = OwnStub(server_->address());
    grpc::ClientContext ctx;
    v1::CacheStatsResponse stats;
    grpc::Status s = stub->GetCacheStats(&ctx, v1::CacheStatsRequest(), &stats);
    ASSERT_TRUE(s.ok()) << s.error_message();
    EXPECT_TRUE(stats.damaged());
    EXPECT_EQ(stats.sets(), static_cast<int64_t>(keys.size() - lost.size()));
  }
  server_->Stop(SIGTERM);

  // verify lists every unreadable key and exits 1.
  const std::string cli = std::string(ALIGNSET_CLI_PATH) + " ";
  auto verify = RunCommand(cli + "cache verify --db " + db);
  EXPECT_EQ(verify.exit_code, 1) << verify.output;
  for (const std::string& k : lost) {
    EXPECT_NE(verify.output.find("DAMAGED " + k + "\n"), std::string::npos) << k << "\n" << verify.output;
  }
  size_t listed = 0;
  for (size_t at = 0; (at = verify.output.find("DAMAGED ", at)) != std::string::npos; ++at) ++listed;
  EXPECT_EQ(listed, lost.size()) << verify.output;

  // recover copies out the rest; the new file verifies clean and serves.
  const std::string fresh = dir_.path() + "/recovered.sqlite";
  auto recover = RunCommand(cli + "cache recover --db " + db + " -o " + fresh);
  ASSERT_EQ(recover.exit_code, 0) << recover.output;
  EXPECT_NE(recover.output.find("recovered " + std::to_string(keys.size() - lost.size()) + " sets"),
            std::string::npos)
      << recover.output;
  auto clean = RunCommand(cli + "cache verify --db " + fresh);
  EXPECT_EQ(clean.exit_code, 0) << clean.output;
  std::filesystem::rename(fresh, db);
  StartServer(With(kFast, {"--metrics-listen", "127.0.0.1:0", "--log-level", "info"}));
  // The background check's line comes after its metric.
  EXPECT_TRUE(server_->WaitForLog({"passed quick_check"}, 1, 20s)) << Log();
  const auto m = ParsePrometheus(HttpRequest(server_->metrics_port(), "GET", "/metrics").body);
  EXPECT_EQ(m.at("alignset_integrity_checks_total"), 1.0);
  EXPECT_EQ(m.at("alignset_database_integrity_errors"), 0.0);
  auto stub = OwnStub(server_->address());
  grpc::ClientContext ctx;
  v1::CacheStatsResponse stats;
  ASSERT_TRUE(stub->GetCacheStats(&ctx, v1::CacheStatsRequest(), &stats).ok());
  EXPECT_FALSE(stats.damaged());
  EXPECT_EQ(stats.sets(), static_cast<int64_t>(keys.size() - lost.size()));
}

// ------------------------------------------------------------- item 8

namespace rpb = grpc::reflection::v1alpha;

// One list_services request on a reflection stream.
grpc::Status ListServices(const std::string& address, const std::string& token,
                          std::vector<std::string>* names) {
  auto stub = rpb::ServerReflection::NewStub(OwnChannel(address));
  grpc::ClientContext ctx;
  if (!token.empty()) ctx.AddMetadata("authorization", "Bearer " + token);
  auto stream = stub->ServerReflectionInfo(&ctx);
  rpb::ServerReflectionRequest req;
  req.set_list_services("");
  rpb::ServerReflectionResponse resp;
  if (stream->Write(req) && stream->Read(&resp)) {
    for (const auto& s : resp.list_services_response().service()) names->push_back(s.name());
  }
  stream->WritesDone();
  while (stream->Read(&resp)) {
  }
  return stream->Finish();
}

TEST_F(HardeningTest, ReflectionDescribesTheServiceFromItsDescriptors) {
  StartServer(kFast);
  std::vector<std::string> names;
  ASSERT_TRUE(ListServices(server_->address(), "", &names).ok());
  EXPECT_NE(std::find(names.begin(), names.end(), "alignset.v1.AlignSet"), names.end());

  auto stub = rpb::ServerReflection::NewStub(OwnChannel(server_->address()));
  grpc::ClientContext ctx;
  auto stream = stub->ServerReflectionInfo(&ctx);
  rpb::ServerReflectionRequest req;
  req.set_file_containing_symbol("alignset.v1.AlignSet");
  rpb::ServerReflectionResponse resp;
  ASSERT_TRUE(stream->Write(req));
  ASSERT_TRUE(stream->Read(&resp));
  ASSERT_TRUE(resp.has_file_descriptor_response());
  bool found = false;
  for (const std::string& bytes : resp.file_descriptor_response().file_descriptor_proto()) {
    google::protobuf::FileDescriptorProto file;
    ASSERT_TRUE(file.ParseFromString(bytes));
    for (const auto& service : file.service()) {
      if (service.name() != "AlignSet") continue;
      found = true;
      EXPECT_EQ(file.package(), "alignset.v1");
      EXPECT_EQ(service.method(0).name(), "GetAlignedSet");
    }
  }
  EXPECT_TRUE(found);
  req.set_file_containing_symbol("alignset.v1.NoSuchThing");
  ASSERT_TRUE(stream->Write(req));
  ASSERT_TRUE(stream->Read(&resp));
  EXPECT_EQ(resp.error_response().error_code(), static_cast<int>(grpc::StatusCode::NOT_FOUND));
  stream->WritesDone();
  EXPECT_TRUE(stream->Finish().ok());
}

TEST_F(HardeningTest, ReflectionFollowsTheTokenAndRefusedCallsAreCountedApart) {
  const std::string token_file = dir_.path() + "/token";
  std::ofstream(token_file) << "s3cret\n";
  StartServer(With(kFast, {"--token-file", token_file}));
  std::vector<std::string> names;
  grpc::Status s = ListServices(server_->address(), "", &names);
  EXPECT_EQ(s.error_code(), grpc::StatusCode::UNAUTHENTICATED) << s.error_message();
  EXPECT_TRUE(names.empty());
  s = ListServices(server_->address(), "s3cret", &names);
  EXPECT_TRUE(s.ok()) << s.error_message();
  EXPECT_NE(std::find(names.begin(), names.end(), "alignset.v1.AlignSet"), names.end());

  auto stub = OwnStub(server_->address());
  for (std::string token : {"", "guess", "s3cret"}) {
    grpc::ClientContext ctx;
    if (!token.empty()) ctx.AddMetadata("authorization", "Bearer " + token);
    v1::AlignedSetResponse resp;
    s = stub->GetAlignedSet(&ctx, SetRequest(64, {5.0}), &resp);
    EXPECT_EQ(s.ok(), token == "s3cret") << token << ": " << s.error_message();
  }
  const v1::MetricsResponse m = GetMetrics(server_->address(), "s3cret");
  EXPECT_EQ(m.requests_get(), 1u);               // the authorized call only
  EXPECT_EQ(m.requests_unauthenticated(), 3u);   // reflection and two GetAlignedSet
  // Without TLS the token travels in clear text: the server says so at start.
  EXPECT_NE(Log().find("travels in clear text"), std::string::npos) << Log();
}

TEST_F(HardeningTest, TlsKeyOfAnotherCertificateIsReportedAsSuch) {
  const std::string d = dir_.path();
  for (const char* name : {"a", "b"}) {
    auto gen = RunCommand("openssl req -x509 -newkey ec -pkeyopt ec_paramgen_curve:prime256v1 -nodes "
                          "-days 1 -subj /CN=localhost -keyout " + d + "/" + name + ".key -out " + d + "/" +
                          name + ".pem");
    ASSERT_EQ(gen.exit_code, 0) << gen.output;
  }
  auto r = RunCommand("timeout 20 " + ServerBinary() + " --listen 127.0.0.1:0 --db " + d +
                      "/x.sqlite --tls-cert " + d + "/a.pem --tls-key " + d + "/b.key");
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.output.find("does not match the certificate"), std::string::npos) << r.output;
  r = RunCommand("timeout 20 " + ServerBinary() + " --listen 127.0.0.1:0 --db " + d +
                 "/x.sqlite --tls-cert " + d + "/a.key --tls-key " + d + "/a.key");
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.output.find("holds no PEM certificate"), std::string::npos) << r.output;
}

}  // namespace
}  // namespace alignset::e2e

// The Prometheus endpoint (issue 15, Operations): GET /metrics on its own
// port, fetched over a plain HTTP socket from the real server on loopback.
#include <google/protobuf/descriptor.h>
#include <gtest/gtest.h>

#include "alignset/v1/alignset.grpc.pb.h"
#include "tests/e2e/e2e_util.h"
#include "tests/e2e/server_process.h"

namespace alignset::e2e {
namespace {

const std::vector<std::string> kMetricsServer = {
    "--max-iterations", "60",  "--workers",        "1",          "--threads-per-worker",
    "1",                "--max-n", "4096",         "--metrics-listen", "127.0.0.1:0"};

std::map<std::string, double> Scrape(int port) {
  const HttpReply r = HttpRequest(port, "GET", "/metrics");
  EXPECT_EQ(r.status, 200) << r.headers;
  EXPECT_NE(r.headers.find("text/plain; version=0.0.4"), std::string::npos) << r.headers;
  return ParsePrometheus(r.body);
}

TEST(MetricsEndpoint, CountersAndHistogramsMoveAfterRequestsAndMatchGetMetrics) {
  TempDir dir;
  ServerProcess server(dir.path(), kMetricsServer);
  ASSERT_EQ(server.error(), "");
  ASSERT_GT(server.metrics_port(), 0);
  ASSERT_NE(server.metrics_port(), server.port());

  const auto before = Scrape(server.metrics_port());
  EXPECT_EQ(before.at("alignset_requests_get_total"), 0.0);
  EXPECT_EQ(before.at("alignset_optimizations_completed_total"), 0.0);
  EXPECT_EQ(before.at("alignset_get_latency_seconds_count"), 0.0);
  EXPECT_EQ(before.at("alignset_database_writable"), 1.0);
  // Every field GetMetrics reports is exposed.
  const auto* fields = v1::MetricsResponse::descriptor();
  for (int i = 0; i < fields->field_count(); ++i) {
    const std::string name = "alignset_" + fields->field(i)->name();
    const bool text = fields->field(i)->cpp_type() == google::protobuf::FieldDescriptor::CPPTYPE_STRING;
    EXPECT_TRUE(text ? before.lower_bound(name + "_info{") != before.end() &&
                           before.lower_bound(name + "_info{")->first.rfind(name + "_info{", 0) == 0
                     : before.count(name) || before.count(name + "_total"))
        << name;
  }

  auto stub = OwnStub(server.address());
  for (int i = 0; i < 2; ++i) {  // optimized, then a hit
    grpc::ClientContext ctx;
    v1::AlignedSetResponse resp;
    ASSERT_TRUE(stub->GetAlignedSet(&ctx, SetRequest(64, {10.0}), &resp).ok());
  }
  {
    grpc::ClientContext ctx;
    v1::AlignedSetResponse resp;
    EXPECT_EQ(stub->GetAlignedSet(&ctx, SetRequest(7, {10.0}), &resp).error_code(),
              grpc::StatusCode::INVALID_ARGUMENT);
  }

  const auto after = Scrape(server.metrics_port());
  EXPECT_EQ(after.at("alignset_requests_get_total"), 3.0);
  EXPECT_EQ(after.at("alignset_requests_invalid_total"), 1.0);
  EXPECT_EQ(after.at("alignset_optimizations_started_total"), 1.0);
  EXPECT_EQ(after.at("alignset_optimizations_completed_total"), 1.0);
  EXPECT_EQ(after.at("alignset_cache_hits_memory_total"), 1.0);
  EXPECT_EQ(after.at("alignset_get_latency_seconds_count"), 3.0);
  EXPECT_EQ(after.at("alignset_get_latency_seconds_bucket{le=\"+Inf\"}"), 3.0);
  EXPECT_EQ(after.at("alignset_optimization_seconds_count"), 1.0);
  EXPECT_GT(after.at("alignset_optimize_seconds_total"), 0.0);
  EXPECT_GT(after.at("alignset_uptime_seconds"), before.at("alignset_uptime_seconds"));
  // The same figures as GetMetrics (which the scrape itself does not move).
  const v1::MetricsResponse m = GetMetrics(server.address());
  EXPECT_EQ(after.at("alignset_requests_get_total"), static_cast<double>(m.requests_get()));
  EXPECT_EQ(after.at("alignset_cache_misses_total"), static_cast<double>(m.cache_misses()));
  EXPECT_EQ(after.at("alignset_optimize_seconds_total"), m.optimize_seconds_total());

  EXPECT_EQ(HttpRequest(server.metrics_port(), "GET", "/").status, 404);
  EXPECT_EQ(HttpRequest(server.metrics_port(), "POST", "/metrics").status, 405);
}

// Where the memory is: each cache's bytes against its bound, the process's
// resident set and malloc's figures, and SQLite's own, so that growth in a
// soak can be put down to a part (docs/operations.md, "Memory").
TEST(MetricsEndpoint, MemoryFiguresNameEachCacheAgainstItsBound) {
  TempDir dir;
  std::vector<std::string> args = kMetricsServer;
  for (const char* a : {"--memory-cache-mb", "1", "--lattice-terms-mb", "2"}) args.push_back(a);
  ServerProcess server(dir.path(), args);
  ASSERT_EQ(server.error(), "");
  const v1::MetricsResponse before = GetMetrics(server.address());
  EXPECT_EQ(before.memory_cache_bytes(), 0);
  EXPECT_EQ(before.memory_cache_capacity_bytes(), 1 << 20);
  EXPECT_EQ(before.lattice_terms_bytes(), 0);
  EXPECT_EQ(before.lattice_terms_capacity_bytes(), 2 << 20);
  EXPECT_GT(before.resident_bytes(), 1 << 20);
  // VmRSS = RssAnon + RssFile + RssShmem, read from one /proc/self/status.
  EXPECT_GT(before.resident_anonymous_bytes(), 0);
  EXPECT_GT(before.resident_file_bytes(), 0);
  EXPECT_GE(before.resident_bytes(), before.resident_anonymous_bytes() + before.resident_file_bytes());
  EXPECT_GT(before.heap_allocated_bytes(), 0);
  EXPECT_EQ(before.allocator().rfind(ALIGNSET_SERVER_JEMALLOC ? "jemalloc 5." : "glibc", 0), 0u) << before.allocator();
  EXPECT_GE(before.heap_free_bytes(), 0);
  EXPECT_GT(before.sqlite_memory_bytes(), 0);
  EXPECT_GE(before.sqlite_memory_peak_bytes(), before.sqlite_memory_bytes());

  // 24 aligned lattices of 4096 points (64 KiB of points each; a lattice's
  // search is a tenth of a second, a net's ten seconds): more than the LRU's
  // 1 MiB, so it must have evicted and hold no more than its bound; their
  // searches fill the lattice-term cache, which must stay within its own.
  auto stub = OwnStub(server.address());
  for (int i = 0; i < 24; ++i) {
    grpc::ClientContext ctx;
    v1::AlignedSetRequest req = SetRequest(4096, {1.0 + 3.5 * i});
    req.set_construction("lattice");
    v1::AlignedSetResponse resp;
    ASSERT_TRUE(stub->GetAlignedSet(&ctx, req, &resp).ok()) << i;
  }
  const v1::MetricsResponse after = GetMetrics(server.address());
  EXPECT_GT(after.memory_cache_bytes(), 512 << 10);
  EXPECT_LE(after.memory_cache_bytes(), after.memory_cache_capacity_bytes());
  EXPECT_GT(after.lattice_terms_bytes(), 0);
  EXPECT_LE(after.lattice_terms_bytes(), after.lattice_terms_capacity_bytes());
  EXPECT_GE(after.sqlite_memory_peak_bytes(), after.sqlite_memory_bytes());
  // The scrape says the same (gauges, bytes).
  const auto scraped = Scrape(server.metrics_port());
  EXPECT_EQ(scraped.at("alignset_memory_cache_capacity_bytes"), 1 << 20);
  EXPECT_EQ(scraped.at("alignset_memory_cache_bytes"), static_cast<double>(after.memory_cache_bytes()));
  EXPECT_GT(scraped.at("alignset_resident_bytes"), 0.0);
  // `alignset stats` prints them, each cache against its bound.
  const CommandResult stats = RunCommand(std::string(ALIGNSET_CLI_PATH) + " stats --server " + server.address());
  EXPECT_EQ(stats.exit_code, 0) << stats.output;
  EXPECT_NE(stats.output.find("memory caches     sets "), std::string::npos) << stats.output;
  EXPECT_NE(stats.output.find(" of 1.0 MiB, lattice terms "), std::string::npos) << stats.output;
  EXPECT_NE(stats.output.find(" of 2.0 MiB, SQLite "), std::string::npos) << stats.output;
  EXPECT_NE(stats.output.find("memory            resident "), std::string::npos) << stats.output;
}

TEST(MetricsEndpoint, AMetricsPortInUseFailsTheStartWithAClearMessage) {
  TempDir first_dir, second_dir;
  ServerProcess first(first_dir.path(), kMetricsServer);
  ASSERT_EQ(first.error(), "");
  std::vector<std::string> flags = kMetricsServer;
  flags.back() = "127.0.0.1:" + std::to_string(first.metrics_port());
  ServerProcess second(second_dir.path(), flags);
  ASSERT_NE(second.error(), "");
  EXPECT_NE(second.error().find("cannot serve metrics"), std::string::npos) << second.error();
  EXPECT_NE(second.error().find("already in use"), std::string::npos) << second.error();
}

}  // namespace
}  // namespace alignset::e2e

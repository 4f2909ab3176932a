// Load generator for alignset-server's cache-hit path (a separate client
// process on loopback). Two modes:
//
//   alignset_load_client populate --db PATH --n 4096,65536 --dir 30
//                        [--max-iterations K] [--seed S]
//     stores an Owen-Sobol set under the key and profile that a server
//     started with the same --max-iterations/--seed would look up, so the
//     hit path can be measured without waiting for optimizations.
//
//   alignset_load_client run --server ADDR --n 4096,65536 --dir 30
//                        [--clients 1,8,64] [--seconds 3] [--warmup 0.5]
//     for every N and client count: that many threads, each with its own
//     connection, request the set back to back; prints p50/p99 latency and
//     throughput (requests/s) per row.
#include <malloc.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <string>
#include <thread>
#include <vector>

#include "cli/cli_app.h"
#include <alignset/client.h>
#include "core/align/canonical.h"
#include "core/sampling/owen_sobol.h"
#include "storage/set_cache.h"

namespace {

using alignset::Status;
using Clock = std::chrono::steady_clock;

int Fail(const Status& s) {
  std::fprintf(stderr, "alignset_load_client: %s\n", s.message().c_str());
  return 1;
}

struct LoadOptions {
  std::string db;
  std::string server = alignset::kDefaultServerAddress;
  std::vector<int64_t> n = {4096, 65536};
  std::vector<int64_t> clients = {1, 8, 64};
  double dir = 30.0;
  int64_t max_iterations = 3000;
  int64_t seed = 1;
  double seconds = 3.0;
  double warmup = 0.5;
};

int Populate(const LoadOptions& o) {
  auto cache = alignset::storage::SetCache::Open(o.db);
  if (!cache.ok()) return Fail(cache.status());
  auto canon = alignset::Canonicalize({o.dir});
  if (!canon.ok()) return Fail(canon.status());
  alignset::OptimizerOptions options;
  options.max_iterations = static_cast<int>(o.max_iterations);
  for (int64_t n : o.n) {
    alignset::storage::SetRecord r;
    r.key.n = static_cast<uint32_t>(n);
    r.key.dirs = canon->key;
    r.key.profile = alignset::storage::ProfileId(alignset::DefaultFrequencyParams(r.key.n), options,
                                                 static_cast<uint64_t>(o.seed));
    r.points = alignset::OwenScrambledSobol(r.key.n, static_cast<uint64_t>(o.seed));
    r.engine = "load-bench-populate";
    r.created_unix = static_cast<int64_t>(std::time(nullptr));
    if (Status s = (*cache)->Put(r); !s.ok()) return Fail(s);
    std::printf("stored %s\n", alignset::storage::KeyToString(r.key).c_str());
  }
  return 0;
}

struct Row {
  int64_t n, clients, requests, errors;
  double seconds, p50_ms, p99_ms, max_ms;
};

Row Measure(const std::string& server, uint32_t n, double dir, int clients, double warmup,
            double seconds) {
  std::vector<std::vector<double>> lat(clients);
  std::atomic<int64_t> errors{0};
  std::atomic<int> ready{0};
  const auto start = Clock::now() + std::chrono::milliseconds(200);  // after connecting
  const auto measure_from = start + std::chrono::microseconds(static_cast<int64_t>(warmup * 1e6));
  const auto stop = measure_from + std::chrono::microseconds(static_cast<int64_t>(seconds * 1e6));
  std::vector<std::thread> threads;
  for (int c = 0; c < clients; ++c) {
    threads.emplace_back([&, c] {
      alignset::ConnectOptions o;
      o.address = server;
      o.separate_connection = true;
      auto client = alignset::ServiceClient::Connect(o);
      if (!client.ok()) {
        ++errors;
        return;
      }
      (*client)->Healthy();  // connect before the clock starts
      ++ready;
      std::this_thread::sleep_until(start);
      lat[c].reserve(1 << 16);
      for (;;) {
        const auto t0 = Clock::now();
        if (t0 >= stop) break;
        auto set = (*client)->GetAlignedSet(n, {dir});
        const auto t1 = Clock::now();
        if (!set.ok() || set->points.size() != n) {
          ++errors;
          continue;
        }
        if (t0 >= measure_from) lat[c].push_back(std::chrono::duration<double, std::milli>(t1 - t0).count());
      }
    });
  }
  for (auto& t : threads) t.join();
  std::vector<double> all;
  for (auto& l : lat) all.insert(all.end(), l.begin(), l.end());
  std::sort(all.begin(), all.end());
  auto pct = [&](double q) {
    if (all.empty()) return 0.0;
    return all[std::min(all.size() - 1, static_cast<size_t>(q * (all.size() - 1) + 0.5))];
  };
  return Row{n, clients, static_cast<int64_t>(all.size()), errors.load(), seconds, pct(0.5),
             pct(0.99), all.empty() ? 0.0 : all.back()};
}

int Run(const LoadOptions& o) {
  std::printf("%8s %8s %10s %8s %10s %10s %10s %12s\n", "N", "clients", "requests", "errors",
              "p50_ms", "p99_ms", "max_ms", "requests/s");
  for (int64_t n : o.n) {
    for (int64_t c : o.clients) {
      const Row r = Measure(o.server, static_cast<uint32_t>(n), o.dir, static_cast<int>(c),
                            o.warmup, o.seconds);
      std::printf("%8lld %8lld %10lld %8lld %10.3f %10.3f %10.3f %12.1f\n", (long long)r.n,
                  (long long)r.clients, (long long)r.requests, (long long)r.errors, r.p50_ms,
                  r.p99_ms, r.max_ms, r.requests / r.seconds);
      std::fflush(stdout);
    }
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  // Keep 1 MiB response buffers in the heap: with glibc's default they are
  // mmap'ed and unmapped per request, and the page faults cost as much as
  // the copies (halves the 65536-point p50 here).
  mallopt(M_MMAP_THRESHOLD, 64 << 20);
  mallopt(M_TRIM_THRESHOLD, 256 << 20);
  using alignset::cli::FiniteIn;
  using alignset::cli::IntegerIn;
  LoadOptions o;
  CLI::App app("Load generator for alignset-server's cache-hit path (bench/load_client.cc)",
               "alignset_load_client");
  app.require_subcommand(1);
  CLI::App* populate = app.add_subcommand("populate", "store Owen-Sobol sets under the server's keys");
  populate->add_option("--db", o.db, "the cache file")->required();
  populate->add_option("--max-iterations", o.max_iterations, "the server's --max-iterations")
      ->check(IntegerIn(1, 100000000));
  populate->add_option("--seed", o.seed, "the server's --seed")->check(IntegerIn(0, INT64_MAX));
  CLI::App* run = app.add_subcommand("run", "measure latency and throughput of cache hits");
  run->add_option("--server", o.server, "server address");
  run->add_option("--clients", o.clients, "client counts")->delimiter(',')->check(IntegerIn(1, 4096));
  run->add_option("--seconds", o.seconds, "measured seconds per row")->check(FiniteIn(0.01, 3600));
  run->add_option("--warmup", o.warmup, "unmeasured seconds first")->check(FiniteIn(0, 3600));
  for (CLI::App* c : {populate, run}) {
    c->add_option("--n", o.n, "point counts")->delimiter(',')->check(IntegerIn(16, 1 << 20));
    c->add_option("--dir", o.dir, "direction (degrees)")->check(alignset::cli::FiniteNumber());
  }
  int rc = 0;
  populate->callback([&] { rc = Populate(o); });
  run->callback([&] { rc = Run(o); });
  CLI11_PARSE(app, argc, argv);
  return rc;
}

#include <cstdio>
#include <memory>
#include <string>

#include "cli/commands.h"
#include "cli/service_options.h"

namespace alignset::cli {
namespace {

int Usage(const Status& s) { return ReportError("stats", s, kExitUsage); }
int Failure(const Status& s) { return ReportError("stats", s, kExitFailure); }

struct StatsOptions {
  bool list = false;
  int64_t n = 0;
  int64_t limit = 100;
  ServiceOptions service;
};

int RunStats(const StatsOptions& o) {
  auto client = Connect(o.service);
  if (!client.ok()) return Usage(client.status());
  auto stats = (*client)->GetCacheStats();
  if (!stats.ok()) return Failure(stats.status());
  const ServiceMetrics& m = stats->metrics;
  std::printf("database          %s\n", stats->database_path.c_str());
  std::printf("sets              %lld (%lld one-direction, %lld two-direction), %.1f MiB\n",
              static_cast<long long>(stats->sets), static_cast<long long>(stats->one_direction_sets),
              static_cast<long long>(stats->two_direction_sets), stats->bytes / 1048576.0);
  if (stats->damaged) {
    std::printf("damaged           yes: the file has damaged pages, the counts cover the readable\n"
                "                  sets (stop the server, run 'alignset cache recover')\n");
  }
  std::printf("profile (N=4096)  %s\n", stats->profile_hint.c_str());
  std::printf("uptime            %.0f s\n", m.uptime_seconds);
  std::printf("requests          get %llu, watch %llu, precompute %llu, samples %llu, estimate %llu, "
              "invalid %llu, unauthenticated %llu\n",
              (unsigned long long)m.requests_get, (unsigned long long)m.requests_watch,
              (unsigned long long)m.requests_precompute, (unsigned long long)m.requests_samples,
              (unsigned long long)m.requests_estimate, (unsigned long long)m.requests_invalid,
              (unsigned long long)m.requests_unauthenticated);
  std::printf("cache             hits %llu memory + %llu db, misses %llu, corrupt rows %llu\n",
              (unsigned long long)m.cache_hits_memory, (unsigned long long)m.cache_hits_db,
              (unsigned long long)m.cache_misses, (unsigned long long)m.corrupt_rows);
  std::printf("optimizations     started %llu, completed %llu, cancelled %llu, failed %llu, "
              "shared waits %llu\n",
              (unsigned long long)m.optimizations_started, (unsigned long long)m.optimizations_completed,
              (unsigned long long)m.optimizations_cancelled, (unsigned long long)m.optimizations_failed,
              (unsigned long long)m.shared_waits);
  std::printf("optimize time     total %.2f s, max %.2f s\n", m.optimize_seconds_total,
              m.optimize_seconds_max);
  std::printf("queue             %u waiting, %u running, %u paused (%llu slices yielded), %llu rejected "
              "(full), %llu rejected (client limit)\n",
              m.queue_length, m.running, m.paused, (unsigned long long)m.optimizations_paused,
              (unsigned long long)m.rejected_queue_full, (unsigned long long)m.rejected_client_limit);
  std::printf("calls             %u waiting for a set, %llu rejected (waiting limit)\n", m.waiting_calls,
              (unsigned long long)m.rejected_waiting_limit);
  std::printf("integrity         %llu database errors, %llu sets served but not stored\n",
              (unsigned long long)m.database_integrity_errors, (unsigned long long)m.sets_not_stored);
  // A replica says what it could not serve and what its writer filled; a
  // bounded writer what it evicted (both lines always, so a script can parse
  // them: "no" / "unbounded" when the server is neither).
  std::printf("replica           %s, misses %llu (NOT_FOUND), filled %llu from the writer\n",
              m.read_only ? "yes (read-only)" : "no", (unsigned long long)m.replica_misses,
              (unsigned long long)m.sets_filled);
  if (m.max_cache_bytes > 0) {
    std::printf("bounded file      %.1f of %.1f MiB, evictions %llu (%.1f MiB), vacuums %llu\n",
                m.cache_file_bytes / 1048576.0, m.max_cache_bytes / 1048576.0,
                (unsigned long long)m.cache_evictions, m.cache_evicted_bytes / 1048576.0,
                (unsigned long long)m.cache_vacuums);
  } else {
    std::printf("bounded file      unbounded, evictions %llu\n", (unsigned long long)m.cache_evictions);
  }
  // Where the memory is: a cache at its bound is growth that stops.
  constexpr double kMiB = 1048576.0;
  std::printf("memory            resident %.1f MiB (%.1f anonymous, %.1f files); %s %.1f MiB in use, "
              "%.1f MiB kept\n",
              m.resident_bytes / kMiB, m.resident_anonymous_bytes / kMiB, m.resident_file_bytes / kMiB,
              m.allocator.empty() ? "malloc" : m.allocator.c_str(), m.heap_allocated_bytes / kMiB,
              m.heap_free_bytes / kMiB);
  std::printf("memory caches     sets %.1f of %.1f MiB, lattice terms %.1f of %.1f MiB, "
              "SQLite %.1f MiB (peak %.1f)\n",
              m.memory_cache_bytes / kMiB, m.memory_cache_capacity_bytes / kMiB, m.lattice_terms_bytes / kMiB,
              m.lattice_terms_capacity_bytes / kMiB, m.sqlite_memory_bytes / kMiB,
              m.sqlite_memory_peak_bytes / kMiB);
  if (o.list) {
    auto keys = (*client)->ListCachedSets(static_cast<uint32_t>(o.n), "", static_cast<uint32_t>(o.limit));
    if (!keys.ok()) return Failure(keys.status());
    for (const CachedKey& k : *keys) std::printf("  %s\n", k.text.c_str());
  }
  return kExitOk;
}

}  // namespace

void AddStatsCommand(CLI::App& app) {
  auto o = std::make_shared<StatsOptions>();
  CLI::App* c = AddCommand(app, "stats", "the server's cache contents and metrics");
  c->add_flag("--list", o->list, "also list the cached keys");
  c->add_option("-n,--n", o->n, "with --list: only this N (0: every N)")
      ->check(IntegerIn(0, UINT32_MAX));
  c->add_option("--limit", o->limit, "with --list: at most this many keys (0: no limit)")
      ->capture_default_str()
      ->check(IntegerIn(0, UINT32_MAX));
  AddServiceOptions(c, &o->service);
  OnRun(c, [o] { return RunStats(*o); });
}

}  // namespace alignset::cli

#include <cstdio>
#include <string>

#include "client/args.h"
#include "client/commands.h"
#include "client/service_flags.h"

namespace alignset::cli {
namespace {

int Fail(const Status& s) { return ReportError("stats", s, kExitService); }

}  // namespace

int RunStats(int argc, char** argv) {
  auto args = Args::Parse(argc, argv, ServiceFlags({"n", "limit"}), {"list"});
  if (!args.ok()) return Fail(args.status());
  if (!args->positionals().empty()) {
    return Fail(Status::InvalidArgument("unexpected argument '" + args->positionals()[0] + "'"));
  }
  auto n = args->Int("n", 0, 0, UINT32_MAX);
  if (!n.ok()) return Fail(n.status());
  auto limit = args->Int("limit", 100, 0, UINT32_MAX);
  if (!limit.ok()) return Fail(limit.status());
  auto client = ConnectFromArgs(*args);
  if (!client.ok()) return Fail(client.status());
  auto stats = (*client)->GetCacheStats();
  if (!stats.ok()) return Fail(stats.status());
  const ServiceMetrics& m = stats->metrics;
  std::printf("database          %s\n", stats->database_path.c_str());
  std::printf("sets              %lld (%lld one-direction, %lld two-direction), %.1f MiB\n",
              static_cast<long long>(stats->sets), static_cast<long long>(stats->one_direction_sets),
              static_cast<long long>(stats->two_direction_sets), stats->bytes / 1048576.0);
  std::printf("profile (N=4096)  %s\n", stats->profile_hint.c_str());
  std::printf("uptime            %.0f s\n", m.uptime_seconds);
  std::printf("requests          get %llu, watch %llu, precompute %llu, samples %llu, invalid %llu\n",
              (unsigned long long)m.requests_get, (unsigned long long)m.requests_watch,
              (unsigned long long)m.requests_precompute, (unsigned long long)m.requests_samples,
              (unsigned long long)m.requests_invalid);
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
  std::printf("queue             %u waiting, %u running, %llu rejected (full)\n", m.queue_length,
              m.running, (unsigned long long)m.rejected_queue_full);
  if (args->Has("list")) {
    auto keys = (*client)->ListCachedSets(static_cast<uint32_t>(*n), "", static_cast<uint32_t>(*limit));
    if (!keys.ok()) return Fail(keys.status());
    for (const CachedKey& k : *keys) std::printf("  %s\n", k.text.c_str());
  }
  return 0;
}

}  // namespace alignset::cli

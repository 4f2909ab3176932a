// `alignset cache ...`: maintenance of SQLite cache files (export, import,
// merge of precompute shards, verify, list). Works on the files directly, so
// it needs no running server.
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <string>
#include <vector>

#include "client/args.h"
#include "client/commands.h"
#include "storage/set_cache.h"

namespace alignset::cli {
namespace {

using storage::SetCache;

// Exit codes: 0 success, 1 the command ran but found damaged sets, 2 error.
int Fail(const std::string& sub, const Status& s) {
  return ReportError("cache " + sub, s, kExitUsage);
}

void PrintUsage() {
  std::fprintf(stderr,
               "usage: alignset cache <subcommand> [options]\n"
               "  export --db PATH --out FILE     consistent copy of the cache (FILE must not exist)\n"
               "  import --db PATH FILE...        merge shard files into the cache\n"
               "  merge  --out FILE SHARD...      merge shard files into a new file\n"
               "  verify --db PATH                re-read every set and check its checksum\n"
               "  list   --db PATH [--n N] [--profile ID]\n"
               "                                  one line per cached set, then totals\n"
               "exit status: 0 ok, 1 damaged sets found (and skipped), 2 error\n");
}

StatusOr<std::unique_ptr<SetCache>> OpenDb(const Args& args, bool read_only) {
  auto db = args.String("db", "");
  if (!db.ok()) return db.status();
  if (db->empty()) return Status::InvalidArgument("--db is required");
  if (read_only && !std::filesystem::exists(*db)) return Status::NotFound(*db + " does not exist");
  SetCache::Options options;
  options.read_only = read_only;
  return SetCache::Open(*db, options);
}

// Merges every file into `cache`; returns the exit status.
int MergeAll(const std::string& sub, SetCache& cache, const std::vector<std::string>& files) {
  int64_t corrupt = 0;
  for (const std::string& f : files) {
    if (!std::filesystem::exists(f)) return Fail(sub, Status::NotFound(f + " does not exist"));
    auto r = cache.MergeFrom(f);
    if (!r.ok()) return Fail(sub, Status(r.status()));
    std::printf("%s: added %lld, already present %lld, damaged (skipped) %lld\n", f.c_str(),
                static_cast<long long>(r->added), static_cast<long long>(r->skipped_existing),
                static_cast<long long>(r->skipped_corrupt));
    corrupt += r->skipped_corrupt;
  }
  return corrupt > 0 ? 1 : 0;
}

int RunExport(int argc, char** argv) {
  auto args = Args::Parse(argc, argv, {"db", "out"});
  if (!args.ok()) return Fail("export", args.status());
  if (!args->positionals().empty()) {
    return Fail("export", Status::InvalidArgument("unexpected argument '" + args->positionals()[0] + "'"));
  }
  auto out = args->String("out", "");
  if (!out.ok() || out->empty()) return Fail("export", Status::InvalidArgument("--out is required"));
  auto cache = OpenDb(*args, true);
  if (!cache.ok()) return Fail("export", cache.status());
  Status s = (*cache)->ExportTo(*out);
  if (!s.ok()) return Fail("export", s);
  auto stats = (*cache)->Stats();
  if (!stats.ok()) return Fail("export", stats.status());
  std::printf("exported %lld sets to %s\n", static_cast<long long>(stats->sets), out->c_str());
  return 0;
}

int RunImport(int argc, char** argv) {
  auto args = Args::Parse(argc, argv, {"db"});
  if (!args.ok()) return Fail("import", args.status());
  if (args->positionals().empty()) return Fail("import", Status::InvalidArgument("name at least one FILE"));
  auto cache = OpenDb(*args, false);
  if (!cache.ok()) return Fail("import", cache.status());
  return MergeAll("import", **cache, args->positionals());
}

int RunMerge(int argc, char** argv) {
  namespace fs = std::filesystem;
  auto args = Args::Parse(argc, argv, {"out"});
  if (!args.ok()) return Fail("merge", args.status());
  auto out = args->String("out", "");
  if (!out.ok() || out->empty()) return Fail("merge", Status::InvalidArgument("--out is required"));
  if (args->positionals().empty()) return Fail("merge", Status::InvalidArgument("name at least one SHARD"));
  if (fs::exists(*out)) {
    return Fail("merge", Status::InvalidArgument(*out + " already exists (use 'cache import' to add to it)"));
  }
  // Built under a temporary name and renamed when complete, so a failed or
  // interrupted merge never leaves a partial FILE behind.
  const std::string tmp = *out + ".partial";
  std::error_code ec;
  for (const char* suffix : {"", "-wal", "-shm"}) fs::remove(tmp + suffix, ec);
  int rc = 0;
  {
    auto cache = SetCache::Open(tmp);
    if (!cache.ok()) return Fail("merge", cache.status());
    rc = MergeAll("merge", **cache, args->positionals());
  }  // closing the last connection checkpoints and removes the WAL
  if (rc == 2) {
    for (const char* suffix : {"", "-wal", "-shm"}) fs::remove(tmp + suffix, ec);
    return rc;
  }
  fs::rename(tmp, *out, ec);
  if (ec) return Fail("merge", Status::Internal("rename " + tmp + ": " + ec.message()));
  std::printf("wrote %s\n", out->c_str());
  return rc;
}

int RunVerify(int argc, char** argv) {
  auto args = Args::Parse(argc, argv, {"db"});
  if (!args.ok()) return Fail("verify", args.status());
  auto cache = OpenDb(*args, true);
  if (!cache.ok()) return Fail("verify", cache.status());
  auto report = (*cache)->Verify();
  if (!report.ok()) return Fail("verify", report.status());
  for (const storage::SetKey& k : report->corrupt) {
    std::printf("DAMAGED %s\n", storage::KeyToString(k).c_str());
  }
  std::printf("checked %lld sets, %zu damaged\n", static_cast<long long>(report->checked),
              report->corrupt.size());
  return report->corrupt.empty() ? 0 : 1;
}

std::string FormatTime(int64_t unix_seconds) {
  const std::time_t t = static_cast<std::time_t>(unix_seconds);
  std::tm tm{};
  gmtime_r(&t, &tm);
  char buf[32];
  std::strftime(buf, sizeof(buf), "%Y-%m-%dT%H:%M:%SZ", &tm);
  return buf;
}

int RunList(int argc, char** argv) {
  auto args = Args::Parse(argc, argv, {"db", "n", "profile"});
  if (!args.ok()) return Fail("list", args.status());
  std::optional<uint32_t> n;
  if (args->Has("n")) {
    auto v = args->Int("n", 0, 1, UINT32_MAX);
    if (!v.ok()) return Fail("list", v.status());
    n = static_cast<uint32_t>(*v);
  }
  std::optional<std::string> profile;
  if (args->Has("profile")) {
    auto v = args->String("profile", "");
    if (!v.ok()) return Fail("list", v.status());
    profile = *v;
  }
  auto cache = OpenDb(*args, true);
  if (!cache.ok()) return Fail("list", cache.status());
  auto rows = (*cache)->ListSummaries(n, profile);
  if (!rows.ok()) return Fail("list", rows.status());
  std::printf("%8s %-8s %-16s %12s %12s %12s %7s %9s %-8s %-20s %3s %10s\n", "n", "dirs", "profile",
              "loss", "spectrum", "sw", "iters", "seconds", "engine", "created", "alg", "bytes");
  for (const storage::SetSummary& s : *rows) {
    std::string dirs = std::to_string(s.key.dirs.phi1);
    if (s.key.dirs.count == 2) {
      dirs += ',';
      dirs += std::to_string(s.key.dirs.phi2);
    }
    std::printf("%8u %-8s %-16s %12.5g %12.5g %12.5g %7d %9.2f %-8s %-20s %3d %10lld\n", s.key.n,
                dirs.c_str(), s.key.profile.c_str(), s.loss.total, s.loss.spectrum, s.loss.sw,
                s.iterations, s.optimize_seconds, s.engine.c_str(), FormatTime(s.created_unix).c_str(),
                s.algorithm_version, static_cast<long long>(s.bytes));
  }
  auto stats = (*cache)->Stats();
  if (!stats.ok()) return Fail("list", stats.status());
  std::printf("%zu listed; the file holds %lld sets (%lld one-direction, %lld two-direction), "
              "%lld bytes of points\n",
              rows->size(), static_cast<long long>(stats->sets), static_cast<long long>(stats->one_direction_sets),
              static_cast<long long>(stats->two_direction_sets), static_cast<long long>(stats->bytes));
  return 0;
}

}  // namespace

int RunCache(int argc, char** argv) {
  if (argc < 1) {
    PrintUsage();
    return 2;
  }
  const std::string sub = argv[0];
  if (sub == "export") return RunExport(argc - 1, argv + 1);
  if (sub == "import") return RunImport(argc - 1, argv + 1);
  if (sub == "merge") return RunMerge(argc - 1, argv + 1);
  if (sub == "verify") return RunVerify(argc - 1, argv + 1);
  if (sub == "list") return RunList(argc - 1, argv + 1);
  if (sub == "--help" || sub == "-h" || sub == "help") {
    PrintUsage();
    return 0;
  }
  ReportError("cache", Status::InvalidArgument("unknown subcommand '" + sub + "'"), kExitUsage);
  PrintUsage();
  return kExitUsage;
}

}  // namespace alignset::cli

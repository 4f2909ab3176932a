// `alignset cache ...`: maintenance of SQLite cache files (export, import,
// merge of precompute shards, verify, recover, list, diff). Works on the
// files directly, so it needs no running server.
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "cli/commands.h"
#include "storage/cache_diff.h"
#include "storage/cache_recovery.h"
#include "storage/partial_file.h"
#include "storage/set_cache.h"

namespace alignset::cli {
namespace {

using storage::SetCache;

struct CacheOptions {
  std::string db;
  std::string out;
  std::vector<std::string> files;
  std::optional<int64_t> n;
  std::optional<std::string> profile;
  bool force = false;  // overwrite an existing OUT.partial
  std::string first, second;  // diff's two files
  bool shared_only = false;    // diff: keys held by one file only are not a difference
};

// Local work: a bad argument or a missing file is a usage error (2), any
// other failure (SQLite, the file system) a failure (1). Damaged sets found
// and skipped are a failure too, reported after the work is done.
int Fail(const std::string& sub, const Status& s) {
  const bool usage = s.code() == Status::Code::kInvalidArgument || s.code() == Status::Code::kNotFound;
  return ReportError("cache " + sub, s, usage ? kExitUsage : kExitFailure);
}

StatusOr<std::unique_ptr<SetCache>> OpenDb(const std::string& db, bool read_only) {
  if (read_only && !std::filesystem::exists(db)) return Status::NotFound(db + " does not exist");
  SetCache::Options options;
  options.read_only = read_only;
  return SetCache::Open(db, options);
}

// Merges every file into `cache`, one line each; returns how many damaged
// sets were skipped.
StatusOr<int64_t> MergeAll(SetCache& cache, const std::vector<std::string>& files) {
  int64_t corrupt = 0;
  for (const std::string& f : files) {
    auto r = cache.MergeFrom(f);
    if (!r.ok()) return Status(r.status());
    std::printf("%s: added %lld, already present %lld, damaged (skipped) %lld\n", f.c_str(),
                static_cast<long long>(r->added), static_cast<long long>(r->skipped_existing),
                static_cast<long long>(r->skipped_corrupt));
    corrupt += r->skipped_corrupt;
  }
  return corrupt;
}

Status CheckInputs(const std::vector<std::string>& files) {
  for (const std::string& f : files) {
    if (!std::filesystem::exists(f)) return Status::NotFound(f + " does not exist");
  }
  return Status::Ok();
}

int RunExport(const CacheOptions& o) {
  if (std::filesystem::exists(o.out)) {
    return Fail("export", Status::InvalidArgument(o.out + " already exists"));
  }
  auto cache = OpenDb(o.db, true);
  if (!cache.ok()) return Fail("export", cache.status());
  Status s = (*cache)->ExportTo(o.out);
  if (!s.ok()) return Fail("export", s);
  auto stats = (*cache)->Stats();
  if (!stats.ok()) return Fail("export", stats.status());
  std::printf("exported %lld sets to %s\n", static_cast<long long>(stats->sets), o.out.c_str());
  return kExitOk;
}

int RunImport(const CacheOptions& o) {
  if (Status s = CheckInputs(o.files); !s.ok()) return Fail("import", s);
  auto cache = OpenDb(o.db, false);
  if (!cache.ok()) return Fail("import", cache.status());
  auto corrupt = MergeAll(**cache, o.files);
  if (!corrupt.ok()) return Fail("import", corrupt.status());
  return *corrupt > 0 ? kExitFailure : kExitOk;
}

int RunMerge(const CacheOptions& o) {
  namespace fs = std::filesystem;
  if (fs::exists(o.out)) {
    return Fail("merge", Status::InvalidArgument(o.out + " already exists (use 'cache import' to add to it)"));
  }
  if (Status s = CheckInputs(o.files); !s.ok()) return Fail("merge", s);
  // Built under a temporary name and renamed when complete, so a failed or
  // interrupted merge never leaves a partial FILE behind.
  const std::string tmp = o.out + ".partial";
  std::error_code ec;
  if (Status s = storage::ClearPartialFile(tmp, o.force); !s.ok()) return Fail("merge", s);
  StatusOr<int64_t> corrupt = Status::Internal("not run");
  {
    auto cache = SetCache::Open(tmp);
    if (!cache.ok()) return Fail("merge", cache.status());
    corrupt = MergeAll(**cache, o.files);
  }  // closing the last connection checkpoints and removes the WAL
  if (!corrupt.ok()) {
    storage::RemovePartialFile(tmp);
    return Fail("merge", corrupt.status());
  }
  fs::rename(tmp, o.out, ec);
  if (ec) return Fail("merge", Status::Internal("rename " + tmp + ": " + ec.message()));
  std::printf("wrote %s\n", o.out.c_str());
  // Damaged sets were skipped: the file is complete but lacks them.
  return *corrupt > 0 ? kExitFailure : kExitOk;
}

// Every set is re-read past damaged pages (storage/cache_recovery.h): each
// unreadable key is listed, with what SQLite and its quick_check said.
int RunVerify(const CacheOptions& o) {
  if (!std::filesystem::exists(o.db)) return Fail("verify", Status::NotFound(o.db + " does not exist"));
  auto check = storage::QuickCheck(o.db);
  if (!check.ok()) return Fail("verify", check.status());
  auto scan = storage::ScanForDamage(o.db);
  if (!scan.ok()) return Fail("verify", scan.status());
  for (const storage::SetKey& k : scan->damaged) {
    std::printf("DAMAGED %s\n", storage::KeyToString(k).c_str());
  }
  for (const std::string& p : *check) std::printf("PAGE %s\n", p.c_str());
  for (const std::string& p : scan->problems) std::printf("READ %s\n", p.c_str());
  const bool damaged = !scan->damaged.empty() || !check->empty() || !scan->problems.empty();
  std::printf("checked %lld sets: %lld readable, %zu damaged; %s\n",
              static_cast<long long>(scan->readable + static_cast<int64_t>(scan->damaged.size())),
              static_cast<long long>(scan->readable), scan->damaged.size(),
              damaged ? "the file is damaged: 'alignset cache recover' copies the readable sets "
                        "into a new file"
                      : "no damage found");
  return damaged ? kExitFailure : kExitOk;
}

// Copies every readable, checksum-valid set into a new file; the lost keys
// are listed (they are recomputed on request).
int RunRecover(const CacheOptions& o) {
  if (!std::filesystem::exists(o.db)) return Fail("recover", Status::NotFound(o.db + " does not exist"));
  auto report = storage::RecoverCache(o.db, o.out, o.force);
  if (!report.ok()) return Fail("recover", report.status());
  for (const storage::SetKey& k : report->lost) std::printf("LOST %s\n", storage::KeyToString(k).c_str());
  std::printf("recovered %lld sets into %s; %zu lost\n", static_cast<long long>(report->recovered),
              o.out.c_str(), report->lost.size());
  return kExitOk;
}

std::string FormatTime(int64_t unix_seconds) {
  const std::time_t t = static_cast<std::time_t>(unix_seconds);
  std::tm tm{};
  gmtime_r(&t, &tm);
  char buf[32];
  std::strftime(buf, sizeof(buf), "%Y-%m-%dT%H:%M:%SZ", &tm);
  return buf;
}

int RunList(const CacheOptions& o) {
  std::optional<uint32_t> n;
  if (o.n) n = static_cast<uint32_t>(*o.n);
  auto cache = OpenDb(o.db, true);
  if (!cache.ok()) return Fail("list", cache.status());
  auto rows = (*cache)->ListSummaries(n, o.profile);
  if (!rows.ok()) return Fail("list", rows.status());
  std::printf("%8s %-11s %-16s %12s %12s %12s %7s %9s %-8s %-20s %3s %10s\n", "n", "dirs [r]", "profile",
              "loss", "spectrum", "sw", "iters", "seconds", "engine", "created", "alg", "bytes");
  for (const storage::SetSummary& s : *rows) {
    std::string dirs = std::to_string(s.key.dirs.phi1);
    if (s.key.dirs.count == 2) {
      dirs += ',';
      dirs += std::to_string(s.key.dirs.phi2);
    }
    if (s.key.realization > 0) dirs += " r" + std::to_string(s.key.realization);
    std::printf("%8u %-11s %-16s %12.5g %12.5g %12.5g %7d %9.2f %-8s %-20s %3d %10lld\n", s.key.n,
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

// Exit 0 when the files agree, 1 when they differ (as diff(1) does), 2 on
// usage. Keys only one file holds are listed and count as a difference
// unless --shared-only (two shards, or two servers that filled different
// keys, agree when every key they share holds the same points).
int RunDiff(const CacheOptions& o) {
  const std::string& a = o.first;
  const std::string& b = o.second;
  if (Status s = CheckInputs({a, b}); !s.ok()) return Fail("diff", s);
  std::optional<uint32_t> n;
  if (o.n) n = static_cast<uint32_t>(*o.n);
  auto first = OpenDb(a, true);
  if (!first.ok()) return Fail("diff", first.status());
  auto second = OpenDb(b, true);
  if (!second.ok()) return Fail("diff", second.status());
  auto diff = storage::DiffCaches(**first, **second, n, o.profile);
  if (!diff.ok()) return Fail("diff", diff.status());
  for (const storage::CacheDiff::Differing& d : diff->differing) {
    std::printf("DIFFERS %s: %lld of %u points\n", storage::KeyToString(d.key).c_str(),
                static_cast<long long>(d.points), d.key.n);
  }
  for (const storage::CacheDiff::Damaged& d : diff->damaged) {
    std::printf("DAMAGED %s in %s\n", storage::KeyToString(d.key).c_str(),
                d.in_first && d.in_second ? "both files" : (d.in_first ? a : b).c_str());
  }
  if (!o.shared_only) {
    for (const storage::SetKey& k : diff->only_first) {
      std::printf("ONLY %s %s\n", a.c_str(), storage::KeyToString(k).c_str());
    }
    for (const storage::SetKey& k : diff->only_second) {
      std::printf("ONLY %s %s\n", b.c_str(), storage::KeyToString(k).c_str());
    }
  }
  const int64_t shared = diff->same + static_cast<int64_t>(diff->differing.size() + diff->damaged.size());
  const bool agree =
      diff->SharedAgree() && (o.shared_only || (diff->only_first.empty() && diff->only_second.empty()));
  std::printf("compared %lld shared sets: %lld the same, %zu differ, %zu damaged; %zu only in %s, "
              "%zu only in %s; %s\n",
              static_cast<long long>(shared), static_cast<long long>(diff->same), diff->differing.size(),
              diff->damaged.size(), diff->only_first.size(), a.c_str(), diff->only_second.size(), b.c_str(),
              agree ? "the files agree" : "the files differ");
  return agree ? kExitOk : kExitFailure;
}

// One cache subcommand: its options and the callback that runs it.
CLI::App* AddSub(CLI::App* cache, const std::string& name, const std::string& description,
                 int (*run)(const CacheOptions&), std::shared_ptr<CacheOptions>* options) {
  auto o = std::make_shared<CacheOptions>();
  CLI::App* c = AddCommand(*cache, name, description);
  OnRun(c, [o, run] { return run(*o); });
  *options = o;
  return c;
}

}  // namespace

void AddCacheCommand(CLI::App& app) {
  CLI::App* cache = AddCommand(app, "cache",
                               "maintain SQLite cache files (export, import, merge, verify, recover, list, diff);\n"
                               "works on the files directly, no server needed");
  cache->require_subcommand(1);
  cache->footer(
      "Exit status: 0 success; 1 failure (damaged sets found and skipped, files that differ,\n"
      "or a SQLite or file system error); 2 usage (a wrong command line, a named file that is\n"
      "missing, an output that already exists).");
  std::shared_ptr<CacheOptions> o;
  CLI::App* c = AddSub(cache, "export", "a consistent copy of the cache (FILE must not exist)",
                       RunExport, &o);
  c->add_option("--db", o->db, "the cache file")->required();
  c->add_option("-o,--out", o->out, "the copy")->required();

  c = AddSub(cache, "import", "merge shard files into the cache", RunImport, &o);
  c->add_option("--db", o->db, "the cache file (created if missing)")->required();
  c->add_option("FILE", o->files, "shard files")->required();

  c = AddSub(cache, "merge", "merge shard files into a new file", RunMerge, &o);
  c->add_option("-o,--out", o->out, "the new file (must not exist)")->required();
  c->add_option("SHARD", o->files, "shard files")->required();
  c->add_flag("--force", o->force, "overwrite an existing OUT.partial");

  c = AddSub(cache, "verify",
             "re-read every set past damaged pages, check checksums and SQLite's quick_check;\n"
             "lists every damaged key (exit 1 when anything is damaged)",
             RunVerify, &o);
  c->add_option("--db", o->db, "the cache file")->required();

  c = AddSub(cache, "recover",
             "copy every readable, checksum-valid set of a damaged cache into a new file\n"
             "(stop the server first; then replace the old file with the new one)",
             RunRecover, &o);
  c->add_option("--db", o->db, "the damaged cache file")->required();
  c->add_option("-o,--out", o->out, "the new file (must not exist)")->required();
  c->add_flag("--force", o->force, "overwrite an existing OUT.partial");

  c = AddSub(cache, "list", "one line per cached set, then totals", RunList, &o);
  c->add_option("--db", o->db, "the cache file")->required();
  c->add_option("-n,--n", o->n, "only this N")->check(IntegerIn(1, UINT32_MAX));
  c->add_option("--profile", o->profile, "only this profile id");

  c = AddSub(cache, "diff",
             "compare two cache files set by set: the points under every shared key, bit for bit\n"
             "(two servers or shards of one deployment must agree); exit 1 when they differ",
             RunDiff, &o);
  c->add_option("FIRST", o->first, "a cache file")->required();
  c->add_option("SECOND", o->second, "the other")->required();
  c->add_option("-n,--n", o->n, "only this N")->check(IntegerIn(1, UINT32_MAX));
  c->add_option("--profile", o->profile, "only this profile id");
  c->add_flag("--shared-only", o->shared_only,
              "keys held by one file only are not a difference (shards, partly filled servers)");
}

}  // namespace alignset::cli

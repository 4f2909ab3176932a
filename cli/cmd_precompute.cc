#include <cstdio>
#include <memory>
#include <sstream>
#include <string>

#include "cli/commands.h"
#include "cli/progress.h"
#include "cli/service_options.h"
#include "core/optimize/construction.h"
#include "core/optimize/optimizer.h"
#include "core/util/number_text.h"

namespace alignset::cli {
namespace {

int Usage(const Status& s) { return ReportError("precompute", s, kExitUsage); }
int Failure(const Status& s) { return ReportError("precompute", s, kExitFailure); }

// "3/8" -> shard 3 of 8 (0-based index).
Status ParseShard(const std::string& text, PrecomputeSpec* spec) {
  const auto slash = text.find('/');
  if (slash == std::string::npos) return Status::InvalidArgument("--shard: expected i/M, got '" + text + "'");
  auto m = ParseInt(text.substr(slash + 1), "--shard count", 1, 1 << 20);
  if (!m.ok()) return m.status();
  auto i = ParseInt(text.substr(0, slash), "--shard index", 0, *m - 1);
  if (!i.ok()) return i.status();
  spec->shard_index = static_cast<uint32_t>(*i);
  spec->shard_count = static_cast<uint32_t>(*m);
  return Status::Ok();
}

struct PrecomputeOptions {
  std::vector<int64_t> n;
  std::string space;  // empty: keys when --key is given, else 1dir
  std::vector<std::string> keys;
  std::string shard;
  int64_t realizations = 1;
  std::string angle_step = "1";  // the one-direction grid: "1" (46 keys) or "0.25" (181)
  std::string construction = "optimized";  // or "lattice", "tent-lattice" or "net"
  ServiceOptions service;
};

int RunPrecompute(const PrecomputeOptions& o) {
  PrecomputeSpec spec;
  for (int64_t n : o.n) spec.n.push_back(static_cast<uint32_t>(n));
  spec.realizations = static_cast<uint32_t>(o.realizations);
  spec.steps_per_degree = o.angle_step == "0.25" ? 4 : 1;
  spec.construction = o.construction;
  const std::string space = !o.space.empty() ? o.space : o.keys.empty() ? "1dir" : "keys";
  if (space == "1dir") {
    spec.space = 1;
  } else if (space == "2dir") {
    spec.space = 2;
  } else {
    spec.space = 0;
  }
  if ((spec.space == 0) != !o.keys.empty()) {
    return Usage(Status::InvalidArgument("--key DEG[,DEG] goes with --space keys (and only with it)"));
  }
  for (const std::string& k : o.keys) {
    std::vector<int> dirs;
    std::stringstream ss(k);
    for (std::string d; std::getline(ss, d, ',');) {
      auto v = ParseInt(d, "--key", -1000000, 1000000);
      if (!v.ok()) return Usage(v.status());
      dirs.push_back(static_cast<int>(*v));
    }
    spec.keys.push_back(dirs);
  }
  if (!o.shard.empty()) {
    if (Status s = ParseShard(o.shard, &spec); !s.ok()) return Usage(s);
  }
  auto client = Connect(o.service);
  if (!client.ok()) return Usage(client.status());

  Progress progress("precompute");
  auto last = (*client)->Precompute(spec, [&](const PrecomputeUpdate& u) {
    char detail[160];
    std::snprintf(detail, sizeof(detail), "optimized %llu, cached %llu, failed %llu, server eta %s",
                  static_cast<unsigned long long>(u.done),
                  static_cast<unsigned long long>(u.cached_already),
                  static_cast<unsigned long long>(u.failed),
                  FormatDuration(u.estimated_seconds_left).c_str());
    progress.Update(static_cast<double>(u.total - u.remaining) + u.running_fraction,
                    static_cast<double>(u.total), detail);
  });
  if (!last.ok()) return Failure(last.status());
  progress.Finish("");
  std::printf("items          %llu\n", static_cast<unsigned long long>(last->total));
  // A lattice or net is constructed, not optimized; the count is the same field.
  std::printf("%s%llu\n", !FindConstruction(o.construction)->optimized() ? "constructed    " : "optimized      ",
              static_cast<unsigned long long>(last->done));
  std::printf("cached already %llu\n", static_cast<unsigned long long>(last->cached_already));
  std::printf("failed         %llu\n", static_cast<unsigned long long>(last->failed));
  std::printf("time           %s\n", FormatDuration(last->elapsed_seconds).c_str());
  if (last->failed > 0) {
    std::fprintf(stderr, "alignset precompute: %llu item(s) failed%s%s\n",
                 static_cast<unsigned long long>(last->failed),
                 last->last_error.empty() ? "" : "; last error: ", last->last_error.c_str());
    return kExitFailure;
  }
  return kExitOk;
}

}  // namespace

void AddPrecomputeCommand(CLI::App& app) {
  auto o = std::make_shared<PrecomputeOptions>();
  CLI::App* c = AddCommand(app, "precompute",
                           "fill the server's cache, with progress and ETA (re-run resumes)");
  c->add_option("-n,--n", o->n, "point counts, comma-separated (e.g. 1024,4096)")
      ->required()
      ->delimiter(',')
      ->check(PointCount());
  c->add_option("--space", o->space,
                "1dir (the 46 one-direction keys), 2dir (the 4141 pairs) or keys (--key)\n"
                "(default: keys with --key, else 1dir)")
      ->check(CLI::IsMember({"1dir", "2dir", "keys"}));
  c->add_option("--key", o->keys, "an explicit key DEG[,DEG], repeatable (with --space keys)")
      ->allow_extra_args(false);
  c->add_option("--shard", o->shard, "this run's shard i/M of the work items (0 <= i < M)");
  c->add_option("-m,--realizations", o->realizations,
                "realizations 0 .. R-1 of every key (each an independent set)")
      ->capture_default_str()
      ->check(IntegerIn(1, SetRequest::kMaxRealization + 1));
  c->add_option("--angle-step", o->angle_step,
                "grid of the one-direction keys in degrees: 1 (the 46 keys) or 0.25 (181 keys,\n"
                "what a default server serves one direction on)")
      ->capture_default_str()
      ->check(CLI::IsMember({"1", "0.25"}));
  c->add_option("--construction", o->construction,
                "optimized (the server's optimized sets), lattice (aligned rank-1 lattices),\n"
                "tent-lattice (those lattices folded by 1 - |2u - 1| after their shift), net\n"
                "(aligned (0,m,2)-nets, N a power of two) or lattice-sequence (aligned lattice\n"
                "sequences, each key's sets at every N prefixes of one), each cached apart")
      ->capture_default_str()
      ->check(ConstructionName());
  AddServiceOptions(c, &o->service);
  OnRun(c, [o] { return RunPrecompute(*o); });
}

}  // namespace alignset::cli

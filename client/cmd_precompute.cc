#include <cstdio>
#include <sstream>
#include <string>

#include "client/args.h"
#include "client/commands.h"
#include "client/progress.h"
#include "client/service_flags.h"

namespace alignset::cli {
namespace {

int Fail(const Status& s) { return ReportError("precompute", s, kExitService); }

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

}  // namespace

int RunPrecompute(int argc, char** argv) {
  auto args = Args::Parse(argc, argv, ServiceFlags({"n", "space", "shard", "key"}));
  if (!args.ok()) return Fail(args.status());
  if (!args->positionals().empty()) {
    return Fail(Status::InvalidArgument("unexpected argument '" + args->positionals()[0] + "'"));
  }
  if (!args->Has("n")) return Fail(Status::InvalidArgument("--n is required (e.g. --n 1024,4096)"));
  PrecomputeSpec spec;
  auto ns = ParseCountList(args->String("n", "").value(), "--n");
  if (!ns.ok()) return Fail(ns.status());
  spec.n = *ns;
  auto space = args->String("space", args->Has("key") ? "keys" : "1dir");
  if (!space.ok()) return Fail(space.status());
  if (*space == "1dir") {
    spec.space = 1;
  } else if (*space == "2dir") {
    spec.space = 2;
  } else if (*space == "keys") {
    spec.space = 0;
  } else {
    return Fail(Status::InvalidArgument("--space must be 1dir, 2dir or keys, got '" + *space + "'"));
  }
  if ((spec.space == 0) != args->Has("key")) {
    return Fail(Status::InvalidArgument("--key DEG[,DEG] goes with --space keys (and only with it)"));
  }
  for (const std::string& k : args->All("key")) {
    std::vector<int> dirs;
    std::stringstream ss(k);
    for (std::string d; std::getline(ss, d, ',');) {
      auto v = ParseInt(d, "--key", -1000000, 1000000);
      if (!v.ok()) return Fail(v.status());
      dirs.push_back(static_cast<int>(*v));
    }
    spec.keys.push_back(dirs);
  }
  if (args->Has("shard")) {
    if (Status s = ParseShard(args->String("shard", "").value(), &spec); !s.ok()) return Fail(s);
  }
  auto client = ConnectFromArgs(*args);
  if (!client.ok()) return Fail(client.status());

  Progress progress("precompute");
  auto last = (*client)->Precompute(spec, [&](const PrecomputeUpdate& u) {
    char detail[160];
    std::snprintf(detail, sizeof(detail), "optimized %llu, cached %llu, failed %llu, server eta %s",
                  static_cast<unsigned long long>(u.done),
                  static_cast<unsigned long long>(u.cached_already),
                  static_cast<unsigned long long>(u.failed),
                  FormatDuration(u.estimated_seconds_left).c_str());
    progress.Update(static_cast<double>(u.total - u.remaining), static_cast<double>(u.total), detail);
  });
  if (!last.ok()) return Fail(last.status());
  progress.Finish("");
  std::printf("items          %llu\n", static_cast<unsigned long long>(last->total));
  std::printf("optimized      %llu\n", static_cast<unsigned long long>(last->done));
  std::printf("cached already %llu\n", static_cast<unsigned long long>(last->cached_already));
  std::printf("failed         %llu\n", static_cast<unsigned long long>(last->failed));
  std::printf("time           %s\n", FormatDuration(last->elapsed_seconds).c_str());
  if (last->failed > 0) {
    std::fprintf(stderr, "alignset precompute: %llu item(s) failed%s%s\n",
                 static_cast<unsigned long long>(last->failed),
                 last->last_error.empty() ? "" : "; last error: ", last->last_error.c_str());
    return 1;
  }
  return 0;
}

}  // namespace alignset::cli

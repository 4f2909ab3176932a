#include <cstdio>
#include <string>

#include "client/args.h"
#include "client/commands.h"
#include "client/point_file.h"
#include "client/progress.h"
#include "client/service_flags.h"

namespace alignset::cli {
namespace {

int Fail(const Status& s) { return ReportError("get", s, kExitService); }

std::string Join(const std::vector<int>& v) {
  std::string s;
  for (int d : v) s += (s.empty() ? "" : ",") + std::to_string(d);
  return s;
}

}  // namespace

int RunGet(int argc, char** argv) {
  auto args = Args::Parse(argc, argv, ServiceFlags({"n", "dir", "out"}), {"quiet"});
  if (!args.ok()) return Fail(args.status());
  if (!args->positionals().empty()) {
    return Fail(Status::InvalidArgument("unexpected argument '" + args->positionals()[0] + "'"));
  }
  if (!args->Has("n")) return Fail(Status::InvalidArgument("--n is required"));
  if (!args->Has("out")) return Fail(Status::InvalidArgument("--out is required"));
  // The server checks N against its own maximum; here only the type.
  auto n = args->Int("n", 0, 0, UINT32_MAX);
  if (!n.ok()) return Fail(n.status());
  auto dirs = args->Doubles("dir");
  if (!dirs.ok()) return Fail(dirs.status());
  if (dirs->empty() || dirs->size() > 2) {
    return Fail(Status::InvalidArgument("give one or two --dir angles (degrees, edge normal), got " +
                                        std::to_string(dirs->size())));
  }
  auto out = args->String("out", "");
  if (!out.ok()) return Fail(out.status());
  auto client = ConnectFromArgs(*args);
  if (!client.ok()) return Fail(client.status());

  // The streaming call shows queue position and optimization progress; a
  // cache hit arrives as its only message.
  Progress progress("optimize");
  bool shown = false;
  const bool quiet = args->Has("quiet");
  auto set = (*client)->WatchAlignedSet(static_cast<uint32_t>(*n), *dirs, [&](const WatchUpdate& u) {
    if (quiet) return;
    shown = true;
    if (u.queued) {
      progress.Update(0, 1, "queued at position " + std::to_string(u.queue_position));
      return;
    }
    char detail[96];
    std::snprintf(detail, sizeof(detail), "loss %.5g lr %.2g", u.loss, u.learning_rate);
    progress.Update(u.iteration, u.max_iterations, detail);
  });
  if (!set.ok()) return Fail(set.status());
  if (shown) progress.Finish("");

  const SetInfo& i = set->info;
  char comment[768];
  std::snprintf(comment, sizeof(comment),
                "alignset served set: N=%u directions(deg, edge normal)=0,90,%s key=%s\n"
                "swap=%d invert=%d loss=%.9g spectrum=%.9g sw=%.9g iterations=%d engine=%s "
                "algorithm_version=%d",
                i.n, Join(i.served_deg).c_str(), i.key_text.c_str(), i.swapped, i.inverted,
                i.loss_total, i.loss_spectrum, i.loss_sw, i.iterations, i.engine.c_str(),
                i.algorithm_version);
  if (Status s = WritePointFile(*out, set->points, comment); !s.ok()) return Fail(s);

  std::printf("N              %u\n", i.n);
  std::printf("directions     0, 90, %s (served; deg, spectral = edge normal)\n",
              Join(i.served_deg).c_str());
  std::printf("canonical key  %s (index %llu)\n", i.key_text.c_str(),
              static_cast<unsigned long long>(i.key_index));
  std::printf("alignment      swap %s, invert x %s\n", i.swapped ? "yes" : "no",
              i.inverted ? "yes" : "no");
  std::printf("loss           %.6g (spectrum %.6g, SW %.6g)\n", i.loss_total, i.loss_spectrum,
              i.loss_sw);
  std::printf("optimization   %d iterations, %.2f s, engine %s, profile %s\n", i.iterations,
              i.optimize_seconds, i.engine.c_str(), i.profile.c_str());
  std::printf("from cache     %s\n", i.from_cache ? "yes" : "no");
  std::printf("wrote          %s\n", out->c_str());
  return 0;
}

}  // namespace alignset::cli

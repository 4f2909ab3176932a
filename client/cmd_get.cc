#include <cstdio>
#include <memory>
#include <string>

#include "client/commands.h"
#include "client/point_file.h"
#include "client/progress.h"
#include "client/service_options.h"

namespace alignset::cli {
namespace {

int Usage(const Status& s) { return ReportError("get", s, kExitUsage); }
int Failure(const Status& s) { return ReportError("get", s, kExitFailure); }

std::string Join(const std::vector<int>& v) {
  std::string s;
  for (int d : v) s += (s.empty() ? "" : ",") + std::to_string(d);
  return s;
}

struct GetOptions {
  int64_t n = 0;
  std::vector<double> dirs;
  std::string out;
  bool quiet = false;
  ServiceOptions service;
};

int RunGet(const GetOptions& o) {
  if (o.dirs.size() > 2) {
    return Usage(Status::InvalidArgument("give one or two --dir angles (degrees, edge normal), got " +
                                         std::to_string(o.dirs.size())));
  }
  auto client = Connect(o.service);
  if (!client.ok()) return Usage(client.status());

  // The streaming call shows queue position and optimization progress; a
  // cache hit arrives as its only message.
  Progress progress("optimize");
  bool shown = false;
  auto set = (*client)->WatchAlignedSet(static_cast<uint32_t>(o.n), o.dirs, [&](const WatchUpdate& u) {
    if (o.quiet) return;
    shown = true;
    if (u.queued) {
      progress.Update(0, 1, "queued at position " + std::to_string(u.queue_position));
      return;
    }
    char detail[96];
    std::snprintf(detail, sizeof(detail), "loss %.5g lr %.2g", u.loss, u.learning_rate);
    progress.Update(u.iteration, u.max_iterations, detail);
  });
  if (!set.ok()) return Failure(set.status());
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
  if (Status s = WritePointFile(o.out, set->points, comment); !s.ok()) return Failure(s);

  FILE* report = ReportStreamFor(o.out);
  std::fprintf(report, "N              %u\n", i.n);
  std::fprintf(report, "directions     0, 90, %s (served; deg, spectral = edge normal)\n",
              Join(i.served_deg).c_str());
  std::fprintf(report, "canonical key  %s (index %llu)\n", i.key_text.c_str(),
              static_cast<unsigned long long>(i.key_index));
  std::fprintf(report, "alignment      swap %s, invert x %s\n", i.swapped ? "yes" : "no",
              i.inverted ? "yes" : "no");
  std::fprintf(report, "loss           %.6g (spectrum %.6g, SW %.6g)\n", i.loss_total, i.loss_spectrum,
              i.loss_sw);
  std::fprintf(report, "optimization   %d iterations, %.2f s, engine %s, profile %s\n", i.iterations,
              i.optimize_seconds, i.engine.c_str(), i.profile.c_str());
  std::fprintf(report, "from cache     %s\n", i.from_cache ? "yes" : "no");
  std::fprintf(report, "wrote          %s\n", o.out.c_str());
  return kExitOk;
}

}  // namespace

void AddGetCommand(CLI::App& app) {
  auto o = std::make_shared<GetOptions>();
  CLI::App* c = AddCommand(app, "get",
                           "an aligned set from alignset-server (.npy or UTK text by extension)");
  // The server checks N against its own maximum; here only the type.
  c->add_option("-n,--n", o->n, "number of points")->required()->check(IntegerIn(0, UINT32_MAX));
  c->add_option("--dir", o->dirs, "direction in degrees (edge normal), once or twice")
      ->required()
      ->allow_extra_args(false)
      ->check(FiniteNumber());
  c->add_option("-o,--out", o->out, "output file: UTK text, .npy, .csv by extension; - stdout")->required();
  c->add_flag("-q,--quiet", o->quiet, "no progress display");
  AddServiceOptions(c, &o->service);
  c->callback([o] { Finish(RunGet(*o)); });
}

}  // namespace alignset::cli

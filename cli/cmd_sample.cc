#include <cstdio>
#include <memory>
#include <optional>
#include <vector>
#include <string>

#include "cli/commands.h"
#include "cli/point_file.h"
#include "core/sampling/samplers.h"
#include "core/sampling/shear.h"

namespace alignset::cli {
namespace {

struct SampleOptions {
  std::string kind;
  int64_t n = 0;
  uint64_t seed = 1;
  double shear = 0.0;
  bool sheared = false;
  std::string out;
  bool list = false;
  // -m: several sets, from the seeds seed, seed + 1, ... (UTK's -m).
  std::optional<int> sets;
};

int Usage(const Status& s) { return ReportError("sample", s, kExitUsage); }

std::string SamplerList() {
  std::string text = "Kinds:\n";
  for (const SamplerInfo& s : Samplers()) {
    char line[256];
    std::snprintf(line, sizeof(line), "  %-22s %s\n", s.name.c_str(), s.description.c_str());
    text += line;
  }
  return text;
}

int RunSample(const SampleOptions& o) {
  if (o.list) {
    std::fputs(SamplerList().c_str(), stdout);
    return kExitOk;
  }
  if (o.kind.empty()) {
    std::string known;
    for (const std::string& n : SamplerNames()) known += (known.empty() ? "" : ", ") + n;
    return Usage(Status::InvalidArgument("expected one sampler KIND (" + known + ")"));
  }
  if (o.n == 0) return Usage(Status::InvalidArgument("--n is required"));
  if (o.out.empty()) return Usage(Status::InvalidArgument("--out is required"));
  const int count = o.sets.value_or(1);
  std::vector<PointSet> sets;
  for (int i = 0; i < count; ++i) {
    auto points = Sample(o.kind, static_cast<uint32_t>(o.n), static_cast<uint64_t>(o.seed + i));
    if (!points.ok()) return Usage(points.status());
    sets.push_back(o.sheared ? Shear(*points, o.shear) : std::move(points).value());
  }
  std::string comment = "alignset sample " + o.kind + " N=" + std::to_string(o.n) +
                        (count > 1 ? " seeds=" + std::to_string(o.seed) + ".." +
                                         std::to_string(o.seed + count - 1)
                                   : " seed=" + std::to_string(o.seed));
  if (o.sheared) {
    comment += " sheared to " + std::to_string(o.shear) + " deg (spectral direction = edge normal)";
  }
  const Status written = o.sets ? WritePointSets(o.out, sets, comment)
                                : WritePointFile(o.out, sets[0], comment);
  if (!written.ok()) return ReportError("sample", written, kExitFailure);
  const std::string sets_text = o.sets ? std::to_string(count) + " sets of " : "";
  std::fprintf(ReportStreamFor(o.out), "wrote %s%lld %s points to %s\n", sets_text.c_str(),
               static_cast<long long>(o.n), o.kind.c_str(), o.out.c_str());
  return kExitOk;
}

}  // namespace

void AddSampleCommand(CLI::App& app) {
  auto o = std::make_shared<SampleOptions>();
  CLI::App* c = AddCommand(app, "sample", "a set from a classic sampler (--list names them)");
  c->add_option("KIND", o->kind, "sampler name (see --list)");
  c->add_option("-n,--n", o->n, "number of points")->check(IntegerIn(1, 1 << 20));
  c->add_option("-s,--seed", o->seed, "seed")->capture_default_str()->check(SeedValue());
  CLI::Option* shear = c->add_option("--shear", o->shear,
                "shear the set (Algorithm 2) so that its dark axis moves onto DEG\n"
                "(spectral direction = edge normal)")
      ->check(FiniteNumber());
  c->add_option("-o,--out", o->out, "output file: UTK text, .npy, .csv by extension; - stdout");
  c->add_option("-m,--sets", o->sets,
                "several sets, from the seeds S, S+1, ...: '#'-separated text, (m, N, 2) .npy")
      ->check(IntegerIn(1, 1 << 16));
  c->add_flag("--list", o->list, "list the sampler kinds and exit");
  c->footer([] { return SamplerList(); });
  OnRun(c, [o, shear] {
    o->sheared = shear->count() > 0;
    return RunSample(*o);
  });
}

}  // namespace alignset::cli

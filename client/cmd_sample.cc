#include <cstdio>
#include <string>

#include "client/args.h"
#include "client/commands.h"
#include "client/point_file.h"
#include "core/sampling/samplers.h"
#include "core/sampling/shear.h"

namespace alignset::cli {
namespace {

int Fail(const Status& s) { return ReportError("sample", s, kExitUsage); }

void PrintSamplers() {
  std::printf("usage: alignset sample KIND --n N [--seed S] [--shear DEG] --out FILE\n"
              "  --shear DEG  shear the set (Algorithm 2) so that its dark axis moves onto\n"
              "               DEG (spectral direction = edge normal)\n\nkinds:\n");
  for (const SamplerInfo& s : Samplers()) {
    std::printf("  %-22s %s\n", s.name.c_str(), s.description.c_str());
  }
}

}  // namespace

int RunSample(int argc, char** argv) {
  auto args = Args::Parse(argc, argv, {"n", "seed", "shear", "out"}, {"help", "list"});
  if (!args.ok()) return Fail(args.status());
  if (args->Has("help") || args->Has("list")) {
    PrintSamplers();
    return 0;
  }
  if (args->positionals().size() != 1) {
    std::string known;
    for (const std::string& n : SamplerNames()) known += (known.empty() ? "" : ", ") + n;
    return Fail(Status::InvalidArgument("expected one sampler KIND (" + known + ")"));
  }
  const std::string kind = args->positionals()[0];
  if (!args->Has("n")) return Fail(Status::InvalidArgument("--n is required"));
  if (!args->Has("out")) return Fail(Status::InvalidArgument("--out is required"));
  auto n = args->Int("n", 0, 1, 1 << 20);
  if (!n.ok()) return Fail(n.status());
  auto seed = args->Int("seed", 1, 0, INT64_MAX);
  if (!seed.ok()) return Fail(seed.status());
  auto out = args->String("out", "");
  if (!out.ok()) return Fail(out.status());

  auto points = Sample(kind, static_cast<uint32_t>(*n), static_cast<uint64_t>(*seed));
  if (!points.ok()) return Fail(points.status());
  std::string comment = "alignset sample " + kind + " N=" + std::to_string(*n) +
                        " seed=" + std::to_string(*seed);
  if (args->Has("shear")) {
    auto shear = args->Double("shear", 0.0);
    if (!shear.ok()) return Fail(shear.status());
    *points = Shear(*points, *shear);
    comment += " sheared to " + std::to_string(*shear) + " deg (spectral direction = edge normal)";
  }
  if (Status s = WritePointFile(*out, *points, comment); !s.ok()) return Fail(s);
  std::printf("wrote %zu %s points to %s\n", points->size(), kind.c_str(), out->c_str());
  return 0;
}

}  // namespace alignset::cli

#include <cstdio>
#include <string>
#include <vector>

#include "client/args.h"
#include "client/commands.h"
#include "client/point_file.h"
#include "core/analysis/step_integrand.h"
#include "core/analysis/variance.h"

namespace alignset::cli {
namespace {

int Fail(const Status& s) { return ReportError("variance", s, kExitUsage); }

}  // namespace

// alignset variance FILE... --normal DEG [--normal DEG ...] [--shifts K] [--seed S]
// Machine-readable CP-rotated variance on step edges through the centre, one
// tab-separated line per (file, normal): file, N, normal, variance, std. error.
// Every set sees the same shifts for a given seed.
int RunVariance(int argc, char** argv) {
  auto args = Args::Parse(argc, argv, {"normal", "shifts", "seed"});
  if (!args.ok()) return Fail(args.status());
  if (args->positionals().empty()) {
    return Fail(Status::InvalidArgument("expected one or more point-set files"));
  }
  auto normals = args->Doubles("normal");
  if (!normals.ok()) return Fail(normals.status());
  if (normals->empty()) return Fail(Status::InvalidArgument("--normal DEG is required"));
  auto shifts = args->Int("shifts", 4096, 16, 1 << 24);
  if (!shifts.ok()) return Fail(shifts.status());
  auto seed = args->Int("seed", 7, 0, INT64_MAX);
  if (!seed.ok()) return Fail(seed.status());
  std::printf("# file\tN\tnormal_deg\tvariance\tstd_error\n");
  for (const std::string& path : args->positionals()) {
    auto points = ReadPointFile(path);
    if (!points.ok()) return Fail(points.status());
    if (points->empty()) return Fail(Status::InvalidArgument(path + ": no points"));
    for (double normal : *normals) {
      const StepIntegrand f(normal);
      const VarianceEstimate v = CranleyPattersonVariance(
          *points, [&f](const Point2& p) { return f(p); }, f.Integral(),
          static_cast<int>(*shifts), static_cast<uint64_t>(*seed));
      std::printf("%s\t%zu\t%.9g\t%.9e\t%.3e\n", path.c_str(), points->size(), normal, v.variance,
                  v.std_error);
    }
  }
  return 0;
}

}  // namespace alignset::cli

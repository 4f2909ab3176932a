#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "cli/commands.h"
#include "cli/point_file.h"
#include "core/analysis/step_integrand.h"
#include "core/analysis/variance.h"

namespace alignset::cli {
namespace {

struct VarianceOptions {
  std::vector<std::string> files;
  std::vector<double> normals;
  int64_t shifts = 4096;
  uint64_t seed = 7;
};

int Usage(const Status& s) { return ReportError("variance", s, kExitUsage); }

// Machine-readable CP-rotated variance on step edges through the centre, one
// tab-separated line per (set, normal): file, N, normal, variance, std. error.
// Every set sees the same shifts for a given seed.
int RunVariance(const VarianceOptions& o) {
  // Every file is read before the first line, so a bad one leaves no output.
  // A file with several sets gives one line per set, named FILE[k].
  std::vector<std::string> names;
  std::vector<PointSet> sets;
  for (const std::string& path : o.files) {
    auto read = ReadPointSets(path);
    if (!read.ok()) return Usage(read.status());
    for (size_t k = 0; k < read->size(); ++k) {
      names.push_back(read->size() > 1 ? path + "[" + std::to_string(k) + "]" : path);
      sets.push_back(std::move((*read)[k]));
    }
  }
  std::printf("# file\tN\tnormal_deg\tvariance\tstd_error\n");
  for (size_t i = 0; i < sets.size(); ++i) {
    const std::string& path = names[i];
    const PointSet* points = &sets[i];
    for (double normal : o.normals) {
      const StepIntegrand f(normal);
      const VarianceEstimate v = CranleyPattersonVariance(
          *points, [&f](const Point2& p) { return f(p); }, f.Integral(),
          static_cast<int>(o.shifts), static_cast<uint64_t>(o.seed));
      std::printf("%s\t%zu\t%.9g\t%.9e\t%.3e\n", path.c_str(), points->size(), normal, v.variance,
                  v.std_error);
    }
  }
  return kExitOk;
}

}  // namespace

void AddVarianceCommand(CLI::App& app) {
  auto o = std::make_shared<VarianceOptions>();
  CLI::App* c = AddCommand(app, "variance",
                           "CP-rotated variance on step edges, one tab-separated line each");
  c->add_option("FILE", o->files, "point-set files (UTK text, .npy, .csv; - stdin), each with one or several sets")->required();
  c->add_option("--normal", o->normals, "edge normal in degrees, repeatable")
      ->required()
      ->allow_extra_args(false)
      ->check(FiniteNumber());
  c->add_option("--shifts", o->shifts, "Cranley-Patterson shifts")
      ->capture_default_str()
      ->check(IntegerIn(16, 1 << 24));
  c->add_option("-s,--seed", o->seed, "seed of the shifts")
      ->capture_default_str()
      ->check(SeedValue());
  OnRun(c, [o] { return RunVariance(*o); });
}

}  // namespace alignset::cli

#include <cstdio>
#include <string>
#include <vector>

#include "client/args.h"
#include "client/commands.h"
#include "client/point_file.h"
#include "core/spectral/direct_engine.h"
#include "core/spectral/frequency_set.h"
#include "core/sampling/owen_sobol.h"
#include "core/analysis/variance.h"

namespace alignset::cli {
namespace {

int Fail(const Status& s) { return ReportError("evaluate", s, kExitUsage); }

// Owen-Sobol varies with its scramble; averaging a few scrambles makes the
// baseline a property of the sampler rather than of one seed.
constexpr int kSobolScrambles = 4;

struct Figures {
  double variance = 0.0;
  double std_error = 0.0;
  std::vector<double> strip_means;
};

Figures Measure(const std::vector<PointSet>& sets, double normal, int edges, int shifts,
                uint64_t seed, const FrequencyParams& params, const std::vector<double>& strips,
                DirectEngine* engine) {
  Figures out;
  out.strip_means.assign(strips.size(), 0.0);
  for (const PointSet& s : sets) {
    const VarianceEstimate v = StepEdgeVariance(s, normal, edges, shifts, seed);
    out.variance += v.variance / sets.size();
    out.std_error += v.std_error / sets.size();
  }
  // One frequency set per strip, shared by every set.
  for (size_t i = 0; i < strips.size(); ++i) {
    engine->SetFrequencies(StripFrequencies(params, strips[i]));
    for (const PointSet& s : sets) {
      SpectrumEvaluation e;
      engine->Evaluate(s, false, &e);
      out.strip_means[i] += e.loss / sets.size();
    }
  }
  return out;
}

}  // namespace

int RunEvaluate(int argc, char** argv) {
  auto args = Args::Parse(argc, argv, {"normal", "shifts", "seed", "dir", "threads", "edges"});
  if (!args.ok()) return Fail(args.status());
  if (args->positionals().size() != 1) {
    return Fail(Status::InvalidArgument("expected exactly one point-set file"));
  }
  if (!args->Has("normal")) return Fail(Status::InvalidArgument("--normal is required"));
  auto normal = args->Double("normal", 0.0);
  if (!normal.ok()) return Fail(normal.status());
  auto shifts = args->Int("shifts", 4096, 1024, 1 << 24);
  if (!shifts.ok()) return Fail(shifts.status());
  auto seed = args->Int("seed", 7, 0, INT64_MAX);
  if (!seed.ok()) return Fail(seed.status());
  auto edges = args->Int("edges", 8, 1, 1024);
  if (!edges.ok()) return Fail(edges.status());
  auto extra = args->Doubles("dir");
  if (!extra.ok()) return Fail(extra.status());
  auto threads = args->Int("threads", 0, 0, 1024);
  if (!threads.ok()) return Fail(threads.status());
  auto points = ReadPointFile(args->positionals()[0]);
  if (!points.ok()) return Fail(points.status());
  const uint32_t n = static_cast<uint32_t>(points->size());

  std::vector<double> strips = {0.0, 90.0, *normal};
  for (double d : *extra) strips.push_back(d);
  const FrequencyParams params = DefaultFrequencyParams(n);
  DirectEngine engine(static_cast<int>(*threads));

  const Figures set = Measure({*points}, *normal, static_cast<int>(*edges), static_cast<int>(*shifts), *seed, params, strips, &engine);
  std::vector<PointSet> sobol;
  for (int i = 0; i < kSobolScrambles; ++i) sobol.push_back(OwenScrambledSobol(n, 1000 + i));
  const Figures base = Measure(sobol, *normal, static_cast<int>(*edges), static_cast<int>(*shifts), *seed, params, strips, &engine);

  std::printf("N %u, %lld parallel step edges with normal %.6g deg (offsets -1/4..1/4), "
              "%lld CP shifts each\n",
              n, static_cast<long long>(*edges), *normal, static_cast<long long>(*shifts));
  std::printf("%-28s %14s %14s\n", "", "this set", "owen-sobol");
  std::printf("%-28s %14.4e %14.4e\n", "variance", set.variance, base.variance);
  std::printf("%-28s %14.2e %14.2e\n", "  (std. error)", set.std_error, base.std_error);
  for (size_t i = 0; i < strips.size(); ++i) {
    char label[64];
    std::snprintf(label, sizeof(label), "mean periodogram %g deg", strips[i]);
    std::printf("%-28s %14.4f %14.4f\n", label, set.strip_means[i], base.strip_means[i]);
  }
  std::printf("variance ratio (owen-sobol / this set): %.3f\n", base.variance / set.variance);
  return 0;
}

}  // namespace alignset::cli

#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "cli/commands.h"
#include "cli/point_file.h"
#include "core/spectral/direct_engine.h"
#include "core/spectral/frequency_set.h"
#include "core/sampling/owen_sobol.h"
#include "core/analysis/variance.h"

namespace alignset::cli {
namespace {

int Usage(const Status& s) { return ReportError("evaluate", s, kExitUsage); }

// Owen-Sobol varies with its scramble; averaging scrambles makes the
// baseline a property of the sampler rather than of one seed. 16 is the
// default because 4 scrambles carry about +-25% noise.
constexpr int kDefaultSobolScrambles = 16;

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

struct EvaluateOptions {
  std::string file;
  double normal = 0.0;
  int64_t shifts = 4096;
  uint64_t seed = 7;
  int64_t edges = 8;
  std::vector<double> extra;
  int64_t threads = 0;
  int64_t scrambles = kDefaultSobolScrambles;
};

int RunEvaluate(const EvaluateOptions& o) {
  auto points = ReadPointFile(o.file);
  if (!points.ok()) return Usage(points.status());
  const uint32_t n = static_cast<uint32_t>(points->size());

  std::vector<double> strips = {0.0, 90.0, o.normal};
  for (double d : o.extra) strips.push_back(d);
  const FrequencyParams params = DefaultFrequencyParams(n);
  DirectEngine engine(static_cast<int>(o.threads));
  const int edges = static_cast<int>(o.edges), shifts = static_cast<int>(o.shifts);
  const uint64_t seed = static_cast<uint64_t>(o.seed);

  const Figures set = Measure({*points}, o.normal, edges, shifts, seed, params, strips, &engine);
  std::vector<PointSet> sobol;
  for (int i = 0; i < o.scrambles; ++i) sobol.push_back(OwenScrambledSobol(n, 1000 + i));
  const Figures base = Measure(sobol, o.normal, edges, shifts, seed, params, strips, &engine);

  std::printf("N %u, %d parallel step edges with normal %.6g deg (offsets -1/4..1/4), "
              "%d CP shifts each\n",
              n, edges, o.normal, shifts);
  std::printf("%-28s %14s %14s\n", "", "this set",
              ("owen-sobol x" + std::to_string(o.scrambles)).c_str());
  std::printf("%-28s %14.4e %14.4e\n", "variance", set.variance, base.variance);
  std::printf("%-28s %14.2e %14.2e\n", "  (std. error)", set.std_error, base.std_error);
  for (size_t i = 0; i < strips.size(); ++i) {
    char label[64];
    std::snprintf(label, sizeof(label), "mean periodogram %g deg", strips[i]);
    std::printf("%-28s %14.4f %14.4f\n", label, set.strip_means[i], base.strip_means[i]);
  }
  std::printf("variance ratio (owen-sobol / this set): %.3f\n", base.variance / set.variance);
  return kExitOk;
}

}  // namespace

void AddEvaluateCommand(CLI::App& app) {
  auto o = std::make_shared<EvaluateOptions>();
  CLI::App* c = AddCommand(app, "evaluate",
                           "CP-rotated variance on parallel step edges and strip periodograms,\n"
                           "beside Owen-scrambled Sobol sets of the same N");
  c->add_option("FILE", o->file, "the point set: UTK text, .npy, .csv; - stdin")->required();
  c->add_option("--normal", o->normal, "edge normal in degrees (the spectral direction)")
      ->required()
      ->check(FiniteNumber());
  c->add_option("--edges", o->edges, "parallel edges at offsets -1/4..1/4")
      ->capture_default_str()
      ->check(IntegerIn(1, 1024));
  c->add_option("--scrambles", o->scrambles, "Owen-Sobol scrambles averaged for the baseline")
      ->capture_default_str()
      ->check(IntegerIn(1, 1024));
  c->add_option("--shifts", o->shifts, "Cranley-Patterson shifts per edge")
      ->capture_default_str()
      ->check(IntegerIn(1024, 1 << 24));
  c->add_option("-s,--seed", o->seed, "seed of the shifts")
      ->capture_default_str()
      ->check(SeedValue());
  c->add_option("--dir", o->extra, "another strip to report (degrees), repeatable")
      ->allow_extra_args(false)
      ->check(FiniteNumber());
  c->add_option("--threads", o->threads, "threads of the spectral engine (0: all cores)")
      ->capture_default_str()
      ->check(IntegerIn(0, 1024));
  OnRun(c, [o] { return RunEvaluate(*o); });
}

}  // namespace alignset::cli

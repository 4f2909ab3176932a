#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "cli/commands.h"
#include "cli/point_file.h"
#include "cli/progress.h"
#include "core/optimize/aligned_lattice.h"
#include "core/optimize/aligned_net.h"
#include "core/optimize/construction.h"
#include "core/optimize/lattice_sequence.h"
#include "core/optimize/optimizer.h"
#include "core/spectral/direction_budget.h"
#include "core/spectral/scaled_loss_engine.h"
#include "core/spectral/spectral_engine.h"
#include "core/util/angles.h"

namespace alignset::cli {
namespace {

struct OptimizeOptions {
  int64_t n = 0;
  std::vector<double> dirs;
  uint64_t seed = 1;
  OptimizerOptions optimizer;
  int64_t threads = 0;
  std::string engine = "auto";
  std::string out;
  // Overrides of the frequency set's shape; unset ones keep the default.
  std::optional<double> length, width, radius;
  // The engine's accuracy during the descent; unset: the profile's.
  std::optional<double> engine_tolerance;
  // -m: several sets, one per seed, written as a multi-set file.
  std::optional<int> sets;
  std::string revert_on = "spectrum";
  // s in L = s L_Spec + c L_SW (core/spectral/scaled_loss_engine.h).
  double spectrum_weight = 1.0;
  // "current" (algorithm version 5) or "supplement" (the paper's flat loss
  // and K, alignset's version 2), for comparisons.
  std::string profile = "current";
  // "optimized" (the descent), "lattice" (an aligned rank-1 lattice,
  // core/optimize/aligned_lattice.h) or "net" (an aligned net,
  // core/optimize/aligned_net.h): the last two need no engine.
  std::string construction = "optimized";
  std::optional<double> window;  // default: 1 degree, 2 for tent-lattice
};

int Usage(const Status& s) { return ReportError("optimize", s, kExitUsage); }
int Failure(const Status& s) { return ReportError("optimize", s, kExitFailure); }

// "30,120": the directions as given, for reports and file comments.
std::string DirectionsText(const std::vector<double>& dirs) {
  std::string text;
  for (double d : dirs) {
    char one[32];
    std::snprintf(one, sizeof(one), "%s%g", text.empty() ? "" : ",", d);
    text += one;
  }
  return text;
}

// Writes a lattice's or net's sets and the report that goes with them.
int WriteConstructed(const OptimizeOptions& o, const std::vector<PointSet>& points, const std::string& comment,
                     const std::string& dir_text, const std::string& construction, double seconds) {
  const Status written = o.sets ? WritePointSets(o.out, points, comment)
                                : WritePointFile(o.out, points[0], comment);
  if (!written.ok()) return Failure(written);
  FILE* report = ReportStreamFor(o.out);
  std::fprintf(report, "N              %u\n", static_cast<uint32_t>(o.n));
  std::fprintf(report, "directions     %s (deg, spectral = edge normal)\n", dir_text.c_str());
  std::fprintf(report, "construction   %s\n", construction.c_str());
  std::fprintf(report, "time           %.3f s\n", seconds);
  std::fprintf(report, "wrote          %s\n", o.out.c_str());
  return kExitOk;
}

// --construction lattice: the generator is searched once; -m gives its
// realizations (seeds S, S+1, ...: other whole-cell shifts of one lattice).
// tent-lattice the same, folded (TentLatticePoints: other continuous shifts
// before the fold).
int RunLattice(const OptimizeOptions& o, const Construction& made) {
  const bool folded = made.folded();
  const double window = o.window.value_or(made.window_deg);
  AlignedLatticeOptions lattice;
  lattice.folded = folded;
  lattice.window_deg = window;
  lattice.threads = static_cast<int>(o.threads);
  const uint32_t n = static_cast<uint32_t>(o.n);
  if (!IsStdStream(o.out)) {
    if (Status s = WritePointFile(o.out, {}, "alignset: construction in progress"); !s.ok()) {
      return Failure(s);
    }
  }
  const auto t0 = std::chrono::steady_clock::now();
  Progress progress(folded ? "tent-lattice search" : "lattice search");
  // In percent: the search reports passes (two for one direction), each
  // with its fractions.
  auto choices = ChooseAlignedLatticeGenerators(n, {o.dirs}, lattice, [&](double done, double total) {
    progress.Update(std::floor(100.0 * done / total), 100.0, "");
  });
  if (!choices.ok()) return Usage(choices.status());
  progress.Finish("");
  const AlignedLatticeChoice* choice = &choices->front();
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const std::string dir_text = DirectionsText(o.dirs);
  const int sets = o.sets.value_or(1);
  std::vector<PointSet> points;
  std::string comment;
  for (int i = 0; i < sets; ++i) {
    const uint64_t seed = o.seed + static_cast<uint64_t>(i);
    points.push_back(LatticePoints(n, choice->generator, seed, folded));
    char line[256];
    std::snprintf(line, sizeof(line),
                  "%salignset aligned %slattice%s: N=%u directions(deg, edge normal)=%s "
                  "generator=%u window=%g seed=%llu",
                  i ? "\n" : "", folded ? "tent-folded " : "",
                  sets > 1 ? (" " + std::to_string(i)).c_str() : "", n,
                  dir_text.c_str(), choice->generator, window,
                  static_cast<unsigned long long>(o.seed + i));
    comment += line;
  }
  char what[160];
  std::snprintf(what, sizeof(what), "aligned %srank-1 lattice, generator %u (%u candidates, window +-%g deg)",
                folded ? "tent-folded " : "", choice->generator, choice->candidates, window);
  return WriteConstructed(o, points, comment, dir_text, what, seconds);
}

// --construction net: -m gives realizations from the seeds S, S+1, ...,
// each its own flip search.
int RunNet(const OptimizeOptions& o, const Construction& made) {
  AlignedNetOptions net;
  const double window = o.window.value_or(made.window_deg);
  net.window_deg = window;
  const uint32_t n = static_cast<uint32_t>(o.n);
  if (!IsStdStream(o.out)) {
    if (Status s = WritePointFile(o.out, {}, "alignset: construction in progress"); !s.ok()) {
      return Failure(s);
    }
  }
  const std::string dir_text = DirectionsText(o.dirs);
  const auto t0 = std::chrono::steady_clock::now();
  const int sets = o.sets.value_or(1);
  std::vector<PointSet> points;
  std::string comment;
  int flips = 0;
  for (int i = 0; i < sets; ++i) {
    auto made = AlignedNet(n, o.dirs, o.seed + static_cast<uint64_t>(i), net);
    if (!made.ok()) return Usage(made.status());
    flips += made->flips;
    points.push_back(std::move(made->points));
    char line[256];
    std::snprintf(line, sizeof(line),
                  "%salignset aligned net%s: N=%u directions(deg, edge normal)=%s window=%g seed=%llu",
                  i ? "\n" : "", sets > 1 ? (" " + std::to_string(i)).c_str() : "", n, dir_text.c_str(),
                  window, static_cast<unsigned long long>(o.seed + i));
    comment += line;
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  char what[160];
  std::snprintf(what, sizeof(what), "aligned (0,m,2)-net, %d flips chosen (window +-%g deg)", flips, window);
  return WriteConstructed(o, points, comment, dir_text, what, seconds);
}

// --construction lattice-sequence: one search for the directions (any N
// reads the same sequence), then -m realizations of its first N points; the
// prefixes' excess over the fixed-size lattices goes to stderr, so a user
// sees how far from the best lattice of each size the sequence is.
int RunSequence(const OptimizeOptions& o, const Construction& made) {
  LatticeSequenceOptions options;
  options.window_deg = o.window.value_or(made.window_deg);
  options.threads = static_cast<int>(o.threads);
  const uint32_t n = static_cast<uint32_t>(o.n);
  if (Status s = made.ValidateSize(n); !s.ok()) return Usage(s);
  if (!IsStdStream(o.out)) {
    if (Status s = WritePointFile(o.out, {}, "alignset: construction in progress"); !s.ok()) {
      return Failure(s);
    }
  }
  const auto t0 = std::chrono::steady_clock::now();
  auto choice = ChooseLatticeSequenceGenerator(o.dirs, options);
  if (!choice.ok()) return Usage(choice.status());
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::fprintf(stderr, "lattice sequence generator %u: prefix score - fixed-size lattice score (log ratio)\n",
               choice->generator);
  for (const LatticeSequenceLevel& level : choice->levels) {
    std::fprintf(stderr, "  N=%-6u %+.3f  (x%.2f; fixed-size generator %u)\n", level.n, level.excess(),
                 std::exp(level.excess()), level.fixed_generator);
  }
  const std::string dir_text = DirectionsText(o.dirs);
  const int sets = o.sets.value_or(1);
  std::vector<PointSet> points;
  std::string comment;
  for (int i = 0; i < sets; ++i) {
    const uint64_t seed = o.seed + static_cast<uint64_t>(i);
    points.push_back(LatticeSequencePoints(n, choice->generator, seed));
    char line[256];
    std::snprintf(line, sizeof(line),
                  "%salignset aligned lattice sequence%s: N=%u directions(deg, edge normal)=%s generator=%u "
                  "window=%g seed=%llu",
                  i ? "\n" : "", sets > 1 ? (" " + std::to_string(i)).c_str() : "", n, dir_text.c_str(),
                  choice->generator, options.window_deg, static_cast<unsigned long long>(seed));
    comment += line;
  }
  char what[160];
  std::snprintf(what, sizeof(what), "aligned rank-1 lattice sequence, generator %u (window +-%g deg)",
                choice->generator, options.window_deg);
  return WriteConstructed(o, points, comment, dir_text, what, seconds);
}

int RunOptimize(const OptimizeOptions& o) {
  if (o.dirs.size() > static_cast<size_t>(kMaxArbitraryDirections)) {
    return Usage(Status::InvalidArgument(
        "give 1 to " + std::to_string(kMaxArbitraryDirections) +
        " --dir angles (degrees; 0 and 90 are always included), got " +
        std::to_string(o.dirs.size())));
  }
  // Two equal --dir are a mistake on the command line, whatever their count
  // (the core takes a repeated pair only for the service's key space).
  for (size_t i = 0; i < o.dirs.size(); ++i) {
    for (size_t j = 0; j < i; ++j) {
      const double gap = std::fabs(ReduceDirection(o.dirs[i]) - ReduceDirection(o.dirs[j]));
      if (std::min(gap, 180.0 - gap) < 1e-9) {
        char text[128];
        std::snprintf(text, sizeof(text), "--dir %g repeats --dir %g (modulo 180)", o.dirs[i],
                      o.dirs[j]);
        return Usage(Status::InvalidArgument(text));
      }
    }
  }
  // The option's check admits known names only.
  const Construction& construction = *FindConstruction(o.construction);
  if (construction.lattice()) return RunLattice(o, construction);
  if (construction.kind == ConstructionKind::kNet) return RunNet(o, construction);
  if (construction.kind == ConstructionKind::kLatticeSequence) return RunSequence(o, construction);
  auto kind = ParseEngineKind(o.engine);
  if (!kind.ok()) return Usage(kind.status());
  const bool supplement = o.profile == "supplement";
  OptimizerOptions options = o.optimizer;
  if (supplement) TurnOffLowFrequencyLevers(&options);
  if (o.engine_tolerance) options.engine_tolerance = *o.engine_tolerance;
  if (o.revert_on == "total") {
    options.divergence_signal = DivergenceSignal::kTotalLoss;
  } else if (o.revert_on != "spectrum") {
    return Usage(Status::InvalidArgument("--revert-on must be spectrum or total, got '" +
                                         o.revert_on + "'"));
  }
  OptimizationProblem problem;
  problem.n = static_cast<uint32_t>(o.n);
  problem.directions = o.dirs;
  problem.seed = static_cast<uint64_t>(o.seed);
  if (o.length || o.width || o.radius || supplement) {
    // The supplement profile keeps Table 1's strips whatever the count.
    const FrequencyParams fp =
        supplement ? SupplementFrequencyParams(problem.n)
                   : FrequencyParamsForDirections(problem.n,
                                                  static_cast<int>(problem.directions.size()));
    problem.frequency_params = FrequencyParams{o.length.value_or(fp.length),
                                               o.width.value_or(fp.width),
                                               o.radius.value_or(fp.radius)};
  }
  if (Status s = ValidateProblem(problem); !s.ok()) return Usage(s);

  // Fail before the work if the output cannot be written.
  if (!IsStdStream(o.out)) {
    if (Status s = WritePointFile(o.out, {}, "alignset: optimization in progress"); !s.ok()) {
      return Failure(s);
    }
  }
  auto made = MakeSpectralEngine(*kind, static_cast<int>(o.threads));
  if (!made.ok()) return Failure(made.status());
  std::unique_ptr<SpectralEngine> inner = std::move(made).value();
  std::unique_ptr<SpectralEngine> scaled;
  if (o.spectrum_weight != 1.0) {
    scaled = std::make_unique<ScaledLossEngine>(*inner, o.spectrum_weight);
  }
  SpectralEngine* engine = scaled ? scaled.get() : inner.get();

  // -m M: M sets from the seeds seed, seed + 1, ... (UTK's -m).
  const int sets = o.sets.value_or(1);
  std::vector<OptimizationResult> results;
  std::vector<double> seconds;
  for (int i = 0; i < sets; ++i) {
    problem.seed = static_cast<uint64_t>(o.seed) + static_cast<uint64_t>(i);
    Progress progress(sets == 1 ? "optimize"
                                : "optimize " + std::to_string(i + 1) + "/" + std::to_string(sets));
    const auto t0 = std::chrono::steady_clock::now();
    auto result = Optimize(problem, options, *engine, [&](const ProgressInfo& p) {
      char detail[160];
      std::snprintf(detail, sizeof(detail), "loss %.5g (spec %.4g sw %.3g) lr %.2g reverts %d",
                    p.loss, p.spectrum_loss, p.sw_loss, p.learning_rate, p.reverts);
      progress.Update(p.iteration, p.max_iterations, detail);
      return true;
    });
    seconds.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    if (!result.ok()) return Failure(result.status());
    progress.Finish("");
    results.push_back(std::move(result).value());
  }

  std::string dir_text;
  for (double d : problem.directions) dir_text += (dir_text.empty() ? "" : ",") + std::to_string(d);
  std::string comment;
  std::vector<PointSet> points;
  for (int i = 0; i < sets; ++i) {
    const OptimizationResult& r = results[i];
    char line[512];
    std::snprintf(line, sizeof(line),
                  "%salignset optimized set%s: N=%u directions(deg, edge normal)=0,90,%s seed=%llu\n"
                  "loss=%.9g spectrum=%.9g sw=%.9g iterations=%d engine=%s",
                  i ? "\n" : "", sets > 1 ? (" " + std::to_string(i)).c_str() : "", problem.n,
                  dir_text.c_str(), static_cast<unsigned long long>(o.seed + i), r.final_loss.total,
                  r.final_loss.spectrum, r.final_loss.sw, r.iterations, engine->name().c_str());
    comment += line;
    points.push_back(r.points);
  }
  const Status written = o.sets ? WritePointSets(o.out, points, comment)
                                : WritePointFile(o.out, points[0], comment);
  if (!written.ok()) return Failure(written);

  FILE* report = ReportStreamFor(o.out);
  const OptimizationResult& first = results[0];
  std::fprintf(report, "N              %u\n", problem.n);
  std::fprintf(report, "directions     0, 90, %s (deg, spectral = edge normal)\n", dir_text.c_str());
  std::fprintf(report, "frequencies    |K| = %zu (length %.1f, width %.2f, radius %.1f)\n",
               first.frequency_count, first.frequency_params.length, first.frequency_params.width,
               first.frequency_params.radius);
  std::fprintf(report, "engine         %s\n", engine->name().c_str());
  for (int i = 0; i < sets; ++i) {
    const OptimizationResult& r = results[i];
    if (sets > 1) {
      std::fprintf(report, "set %-10d seed %llu\n", i, static_cast<unsigned long long>(o.seed + i));
    }
    std::fprintf(report, "loss           %.6g -> %.6g\n", r.initial.total, r.final_loss.total);
    std::fprintf(report, "spectrum loss  %.6g -> %.6g (mean periodogram over K; white noise = 1)\n",
                 r.initial.spectrum, r.final_loss.spectrum);
    std::fprintf(report, "SW loss        %.6g -> %.6g\n", r.initial.sw, r.final_loss.sw);
    std::fprintf(report, "iterations     %d (%s, %d reverts, final learning rate %.3g)\n",
                 r.iterations, StopReasonName(r.stop_reason).c_str(), r.reverts,
                 r.final_learning_rate);
    std::fprintf(report, "time           %.2f s\n", seconds[i]);
  }
  std::fprintf(report, "wrote          %s\n", o.out.c_str());
  return kExitOk;
}

}  // namespace

void AddOptimizeCommand(CLI::App& app) {
  auto o = std::make_shared<OptimizeOptions>();
  CLI::App* c = AddCommand(app, "optimize",
                           "optimize an aligned set locally (no server)\n"
                           "(DEG: spectral direction = edge normal)");
  c->add_option("-n,--n", o->n, "number of points")
      ->required()
      ->check(PointCount());
  c->add_option("--dir", o->dirs,
                "direction in degrees (edge normal), 1 to 8 times: 3 to 10 low-energy\n"
                "directions with the axes (more than two: the strips share the budget)")
      ->required()
      ->allow_extra_args(false)
      ->check(FiniteNumber());
  c->add_option("-s,--seed", o->seed, "seed of the Owen-scrambled Sobol start")
      ->capture_default_str()
      ->check(SeedValue());
  c->add_option("-o,--out", o->out, "output file: UTK text, .npy, .csv by extension; - stdout")
      ->required();
  c->add_option("-m,--sets", o->sets,
                "several sets, from the seeds S, S+1, ...: '#'-separated text, (m, N, 2) .npy")
      ->check(IntegerIn(1, 4096));
  c->add_option("--construction", o->construction,
                "optimized (gradient descent from Owen-scrambled Sobol), lattice (an aligned\n"
                "rank-1 lattice: its generator chosen by the exact variance of step edges\n"
                "within --window degrees of each direction), tent-lattice (the same lattice\n"
                "folded by the tent 1 - |2u - 1| after its shift, its generator chosen for the\n"
                "folded edges: no loss on smooth functions that are not periodic), net (an\n"
                "aligned (0,m,2)-net: its scrambling chosen for those edges; N a power of two)\n"
                "or lattice-sequence (the first N points of an aligned lattice sequence, every\n"
                "power-of-two prefix an aligned lattice: for adaptive sampling; N up to 65536)")
      ->capture_default_str()
      ->check(ConstructionName());
  c->add_option("--window", o->window,
                "lattice, tent-lattice, net, lattice-sequence: the half-width in degrees of the window of edge\n"
                "directions scored (default 1; tent-lattice 2)")
      ->check(FiniteIn(0.0, 10.0));
  c->add_option("--engine", o->engine, "spectral engine: auto, direct, fast or cuda")
      ->capture_default_str();
  c->add_option("--threads", o->threads, "engine threads (0: all cores)")
      ->capture_default_str()
      ->check(IntegerIn(0, 1024));
  const std::string tuning = "Tuning";
  c->add_option("--profile", o->profile,
                "current (the low-frequency levers) or supplement (the paper's flat loss and K)")
      ->capture_default_str()
      ->check(CLI::IsMember({"current", "supplement"}))
      ->group(tuning);
  c->add_option("--max-iterations", o->optimizer.max_iterations,
                "iteration budget (0: 1000 up to N = 4096, then growing like sqrt N)")
      ->check(IntegerIn(0, 100000000))
      ->group(tuning);
  c->add_option("--learning-rate", o->optimizer.learning_rate,
                "first Adam step (0: 0.05 / the largest suppressed frequency)")
      ->check(FiniteNumber())
      ->group(tuning);
  c->add_option("--sw-weight", o->optimizer.sw_weight, "weight c of the SW loss (0: 4N)")
      ->check(FiniteNumber())
      ->group(tuning);
  c->add_option("--spectrum-weight", o->spectrum_weight,
                "weight s of the spectrum loss, L = s L_Spec + c L_SW (0: SW alone)")
      ->check(FiniteIn(0.0, 1e6))
      ->group(tuning);
  c->add_option("--revert-on", o->revert_on,
                "loss the revert rule watches: spectrum (default) or total")
      ->group(tuning);
  c->add_option("--anneal", o->optimizer.anneal_ratio, "final / first learning rate")
      ->check(FiniteNumber())
      ->group(tuning);
  c->add_option("--revert-divisor", o->optimizer.revert_divisor,
                "learning-rate divisor on a revert")
      ->check(FiniteNumber())
      ->group(tuning);
  c->add_option("--engine-tolerance", o->engine_tolerance,
                "accuracy asked of the engine during the descent (0: current 1e-7 up to "
                "N = 4096 and 1e-11 above; supplement 1e-11)")
      ->check(FiniteIn(0.0, 1e-2))
      ->group(tuning);
  c->add_option("--length", o->length, "strip half-length L (default: from N)")
      ->check(FiniteNumber())
      ->group(tuning);
  c->add_option("--width", o->width, "strip width W (default: from N)")
      ->check(FiniteNumber())
      ->group(tuning);
  c->add_option("--radius", o->radius, "disk radius R (default: from N)")
      ->check(FiniteNumber())
      ->group(tuning);
  OnRun(c, [o] { return RunOptimize(*o); });
}

}  // namespace alignset::cli

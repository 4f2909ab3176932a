#include <chrono>
#include <cstdio>
#include <string>

#include "client/args.h"
#include "client/commands.h"
#include "client/point_file.h"
#include "client/progress.h"
#include "core/optimize/optimizer.h"
#include "core/spectral/spectral_engine.h"

namespace alignset::cli {
namespace {

int Fail(const Status& s) { return ReportError("optimize", s, kExitUsage); }

}  // namespace

int RunOptimize(int argc, char** argv) {
  auto args = Args::Parse(argc, argv,
                          {"n", "dir", "seed", "max-iterations", "engine", "threads", "out",
                           "learning-rate", "length", "width", "radius", "sw-weight", "anneal", "revert-divisor"});
  if (!args.ok()) return Fail(args.status());
  if (!args->positionals().empty()) {
    return Fail(Status::InvalidArgument("unexpected argument '" + args->positionals()[0] + "'"));
  }
  if (!args->Has("n")) return Fail(Status::InvalidArgument("--n is required"));
  if (!args->Has("out")) return Fail(Status::InvalidArgument("--out is required"));
  auto n = args->Int("n", 0, kMinPoints, kMaxPoints);
  if (!n.ok()) return Fail(n.status());
  auto dirs = args->Doubles("dir");
  if (!dirs.ok()) return Fail(dirs.status());
  if (dirs->empty() || dirs->size() > 2) {
    return Fail(Status::InvalidArgument("give one or two --dir angles (degrees), got " +
                                        std::to_string(dirs->size())));
  }
  auto seed = args->Int("seed", 1, 0, INT64_MAX);
  if (!seed.ok()) return Fail(seed.status());
  OptimizerOptions options;
  auto iters = args->Int("max-iterations", options.max_iterations, 0, 100000000);
  if (!iters.ok()) return Fail(iters.status());
  options.max_iterations = static_cast<int>(*iters);
  auto lr = args->Double("learning-rate", 0.0);
  if (!lr.ok()) return Fail(lr.status());
  options.learning_rate = *lr;
  auto sw_weight = args->Double("sw-weight", options.sw_weight);
  if (!sw_weight.ok()) return Fail(sw_weight.status());
  options.sw_weight = *sw_weight;
  auto divisor = args->Double("revert-divisor", options.revert_divisor);
  if (!divisor.ok()) return Fail(divisor.status());
  options.revert_divisor = *divisor;
  auto anneal = args->Double("anneal", options.anneal_ratio);
  if (!anneal.ok()) return Fail(anneal.status());
  options.anneal_ratio = *anneal;
  auto threads = args->Int("threads", 0, 0, 1024);
  if (!threads.ok()) return Fail(threads.status());
  auto engine_name = args->String("engine", "auto");
  if (!engine_name.ok()) return Fail(engine_name.status());
  auto kind = ParseEngineKind(*engine_name);
  if (!kind.ok()) return Fail(kind.status());
  auto out = args->String("out", "");
  if (!out.ok()) return Fail(out.status());

  OptimizationProblem problem;
  problem.n = static_cast<uint32_t>(*n);
  problem.directions = *dirs;
  problem.seed = static_cast<uint64_t>(*seed);
  if (args->Has("length") || args->Has("width") || args->Has("radius")) {
    // Overrides of the frequency set's shape; unspecified ones keep the default.
    FrequencyParams fp = DefaultFrequencyParams(problem.n);
    auto length = args->Double("length", fp.length);
    auto width = args->Double("width", fp.width);
    auto radius = args->Double("radius", fp.radius);
    for (const auto* v : {&length, &width, &radius}) {
      if (!v->ok()) return Fail(v->status());
    }
    problem.frequency_params = FrequencyParams{*length, *width, *radius};
  }
  if (Status s = ValidateProblem(problem); !s.ok()) return Fail(s);

  // Fail before the work if the output cannot be written.
  if (Status s = WritePointFile(*out, {}, "alignset: optimization in progress"); !s.ok()) {
    return Fail(s);
  }
  auto engine = MakeSpectralEngine(*kind, static_cast<int>(*threads));
  if (!engine.ok()) return Fail(engine.status());

  Progress progress("optimize");
  const auto t0 = std::chrono::steady_clock::now();
  auto result = Optimize(problem, options, **engine, [&](const ProgressInfo& p) {
    char detail[160];
    std::snprintf(detail, sizeof(detail), "loss %.5g (spec %.4g sw %.3g) lr %.2g reverts %d",
                  p.loss, p.spectrum_loss, p.sw_loss, p.learning_rate, p.reverts);
    progress.Update(p.iteration, p.max_iterations, detail);
    return true;
  });
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (!result.ok()) return Fail(result.status());
  progress.Finish("");

  std::string dir_text;
  for (double d : problem.directions) dir_text += (dir_text.empty() ? "" : ",") + std::to_string(d);
  char comment[512];
  std::snprintf(comment, sizeof(comment),
                "alignset optimized set: N=%u directions(deg, edge normal)=0,90,%s seed=%llu\n"
                "loss=%.9g spectrum=%.9g sw=%.9g iterations=%d engine=%s",
                problem.n, dir_text.c_str(), static_cast<unsigned long long>(problem.seed),
                result->final_loss.total, result->final_loss.spectrum, result->final_loss.sw,
                result->iterations, (*engine)->name().c_str());
  if (Status s = WritePointFile(*out, result->points, comment); !s.ok()) return Fail(s);

  std::printf("N              %u\n", problem.n);
  std::printf("directions     0, 90, %s (deg, spectral = edge normal)\n", dir_text.c_str());
  std::printf("frequencies    |K| = %zu (length %.1f, width %.2f, radius %.1f)\n",
              result->frequency_count, result->frequency_params.length,
              result->frequency_params.width, result->frequency_params.radius);
  std::printf("engine         %s\n", (*engine)->name().c_str());
  std::printf("loss           %.6g -> %.6g\n", result->initial.total, result->final_loss.total);
  std::printf("spectrum loss  %.6g -> %.6g (mean periodogram over K; white noise = 1)\n",
              result->initial.spectrum, result->final_loss.spectrum);
  std::printf("SW loss        %.6g -> %.6g\n", result->initial.sw, result->final_loss.sw);
  std::printf("iterations     %d (%s, %d reverts, final learning rate %.3g)\n", result->iterations,
              StopReasonName(result->stop_reason).c_str(), result->reverts,
              result->final_learning_rate);
  std::printf("time           %.2f s\n", seconds);
  std::printf("wrote          %s\n", out->c_str());
  return 0;
}

}  // namespace alignset::cli

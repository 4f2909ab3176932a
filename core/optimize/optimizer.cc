#include "core/optimize/optimizer.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdio>
#include <memory>
#include <string>

#include "core/optimize/axis_stratification.h"
#include "core/optimize/low_frequency_projection.h"
#include "core/sampling/owen_sobol.h"
#include "core/spectral/direction_budget.h"
#include "core/spectral/fast_engine.h"
#include "core/optimize/sliced_wasserstein.h"

namespace alignset {
namespace {

// Everything the revert rule must be able to restore.
struct AdamState {
  PointSet x;
  std::vector<Point2> m;
  std::vector<Point2> v;
  std::vector<Point2> grad;  // total gradient at x
  LossTerms loss;
  int t = 0;
};

void EvaluateTotal(const PointSet& x, SpectralEngine& engine, const SlicedWasserstein& sw,
                   double sw_weight, SpectrumEvaluation* scratch, std::vector<Point2>* sw_grad,
                   AdamState* state) {
  engine.Evaluate(x, /*with_gradient=*/true, scratch);
  state->loss.spectrum = scratch->loss;
  state->loss.sw = sw.Evaluate(x, sw_grad);
  state->loss.total = state->loss.spectrum + sw_weight * state->loss.sw;
  state->grad.resize(x.size());
  for (size_t j = 0; j < x.size(); ++j) {
    state->grad[j].x = scratch->gradient[j].x + sw_weight * (*sw_grad)[j].x;
    state->grad[j].y = scratch->gradient[j].y + sw_weight * (*sw_grad)[j].y;
  }
}

// One Adam step from `from` (its gradient included) into `to`; `from` is left
// as it was, so a rejected step costs nothing to undo.
void AdamStep(const AdamState& from, const OptimizerOptions& o, double lr, AdamState* to) {
  const size_t n = from.x.size();
  to->x.resize(n);
  to->m.resize(n);
  to->v.resize(n);
  to->t = from.t + 1;
  const double c1 = 1.0 - std::pow(o.beta1, to->t);
  const double c2 = 1.0 - std::pow(o.beta2, to->t);
  auto update = [&](double g, double m0, double v0, double x0, double* m, double* v, double* x) {
    *m = o.beta1 * m0 + (1.0 - o.beta1) * g;
    *v = o.beta2 * v0 + (1.0 - o.beta2) * g * g;
    const double mhat = *m / c1;
    const double vhat = *v / c2;
    *x = Wrap01(x0 - lr * mhat / (std::sqrt(vhat) + o.epsilon));
  };
  for (size_t j = 0; j < n; ++j) {
    update(from.grad[j].x, from.m[j].x, from.v[j].x, from.x[j].x, &to->m[j].x, &to->v[j].x,
           &to->x[j].x);
    update(from.grad[j].y, from.m[j].y, from.v[j].y, from.x[j].y, &to->m[j].y, &to->v[j].y,
           &to->x[j].y);
  }
}

std::string DegreesText(double deg) {
  char text[32];
  std::snprintf(text, sizeof(text), "%g", deg);
  return text;
}

}  // namespace

Status CheckDistinctDirections(const std::vector<double>& arbitrary) {
  const std::vector<double> all = AnisotropyDirections(arbitrary);
  for (size_t i = 0; i < all.size(); ++i) {
    for (size_t j = 0; j < i; ++j) {
      const double gap = std::fabs(all[i] - all[j]);
      if (std::min(gap, 180.0 - gap) < 1e-9) {
        return Status::InvalidArgument(
            "duplicate direction " + DegreesText(all[i]) +
            (j < 2 ? " (0 and 90 are always included)" : " (given twice, modulo 180)"));
      }
    }
  }
  return Status::Ok();
}

bool UsesKeyLineage(const OptimizerOptions& options, uint32_t n) {
  return options.warm_budget_fraction > 0.0 && n >= options.warm_min_points;
}

OptimizerOptions WarmStartOptions(const OptimizerOptions& cold, uint32_t n,
                                  int arbitrary_directions) {
  OptimizerOptions warm = cold;
  const int budget = EffectiveMaxIterations(cold, n, arbitrary_directions);
  warm.max_iterations =
      std::max(1, static_cast<int>(std::lround(cold.warm_budget_fraction * budget)));
  warm.warmup_fraction = n <= cold.warm_warmup_max_points ? cold.warm_warmup_fraction : 0.0;
  if (arbitrary_directions >= 2 && n <= cold.warm_pair_learning_rate_max_points) {
    warm.learning_rate_scale = cold.warm_pair_learning_rate_scale;
  }
  return warm;
}

double DefaultLearningRate(const std::vector<Frequency>& k) {
  double vmax = 1.0;
  for (const Frequency& v : k) vmax = std::max(vmax, std::hypot(v.a, v.b));
  return 0.05 / vmax;
}

double EffectiveSwWeight(const OptimizerOptions& options, uint32_t n) {
  return options.sw_weight > 0.0 ? options.sw_weight : 4.0 * static_cast<double>(n);
}

OptimizerOptions SupplementOptimizerOptions() {
  OptimizerOptions o;
  TurnOffLowFrequencyLevers(&o);
  return o;
}

void TurnOffLowFrequencyLevers(OptimizerOptions* options) {
  options->weighting = {};
  options->warmup_weighting = {};
  options->warmup_fraction = 0.0;
  options->stratify_axes = false;
  options->zero_radius = 0.0;
  options->final_margin = 0.0;
  options->engine_tolerance = FastEngine::kDefaultTolerance;
}

int DefaultIterationBudget(uint32_t n, int arbitrary_directions) {
  constexpr double kBase = 1000.0;
  constexpr double kBaseN = 4096.0;
  const double per_direction = arbitrary_directions >= 2 ? 1.5 : 1.0;
  return static_cast<int>(
      std::lround(kBase * per_direction * std::sqrt(std::max(1.0, n / kBaseN))));
}

double DefaultEngineTolerance(uint32_t n) {
  return n <= 4096 ? 1e-7 : FastEngine::kDefaultTolerance;
}

double EffectiveEngineTolerance(const OptimizerOptions& options, uint32_t n) {
  return options.engine_tolerance > 0.0 ? options.engine_tolerance : DefaultEngineTolerance(n);
}

int EffectiveMaxIterations(const OptimizerOptions& options, uint32_t n, int arbitrary_directions) {
  return options.max_iterations > 0 ? options.max_iterations
                                    : DefaultIterationBudget(n, arbitrary_directions);
}

std::string StopReasonName(StopReason r) {
  switch (r) {
    case StopReason::kMaxIterations: return "iteration budget";
    case StopReason::kStalled: return "stalled";
    case StopReason::kLearningRateFloor: return "learning-rate floor";
    case StopReason::kCancelled: return "cancelled";
  }
  return "unknown";
}

Status ValidateProblem(const OptimizationProblem& p) {
  if (p.n < kMinPoints || p.n > kMaxPoints) {
    return Status::InvalidArgument("point count " + std::to_string(p.n) + " out of range [" +
                                   std::to_string(kMinPoints) + ", " +
                                   std::to_string(kMaxPoints) + "]");
  }
  if (p.directions.empty() || p.directions.size() > kMaxArbitraryDirections) {
    return Status::InvalidArgument("expected 1 to " + std::to_string(kMaxArbitraryDirections) +
                                   " arbitrary directions, got " +
                                   std::to_string(p.directions.size()));
  }
  for (double d : p.directions) {
    if (!std::isfinite(d)) return Status::InvalidArgument("direction must be a finite angle");
  }
  if (p.directions.size() > 2) {
    if (Status s = CheckDistinctDirections(p.directions); !s.ok()) return s;
  }
  if (p.start) {
    if (p.start->size() != p.n) {
      return Status::InvalidArgument("start set has " + std::to_string(p.start->size()) +
                                     " points, expected " + std::to_string(p.n));
    }
    for (const Point2& q : *p.start) {
      if (!(q.x >= 0.0 && q.x < 1.0 && q.y >= 0.0 && q.y < 1.0)) {
        return Status::InvalidArgument("start set has a point outside [0,1)^2");
      }
    }
  }
  if (p.frequency_params) return ValidateFrequencyParams(*p.frequency_params);
  return Status::Ok();
}

static Status ValidateWeighting(const SpectrumWeighting& w) {
  auto bad = [](double v, double lo, double hi) { return !std::isfinite(v) || v < lo || v > hi; };
  if (bad(w.exponent, 0.0, 16.0)) return Status::InvalidArgument("weighting exponent must be in [0, 16]");
  return Status::Ok();
}

Status ValidateOptions(const OptimizerOptions& o) {
  if (o.max_iterations < 0) return Status::InvalidArgument("max_iterations must be >= 0");
  if (!(o.warm_budget_fraction >= 0.0 && o.warm_budget_fraction <= 1.0)) {
    return Status::InvalidArgument("warm_budget_fraction must be in [0, 1]");
  }
  if (!(o.warm_warmup_fraction >= 0.0 && o.warm_warmup_fraction < 1.0)) {
    return Status::InvalidArgument("warm_warmup_fraction must be in [0, 1)");
  }
  if (!(o.learning_rate >= 0.0) || !std::isfinite(o.learning_rate)) {
    return Status::InvalidArgument("learning_rate must be finite and >= 0");
  }
  if (!(o.learning_rate_scale > 0.0) || !std::isfinite(o.learning_rate_scale) ||
      !(o.warm_pair_learning_rate_scale > 0.0) || !std::isfinite(o.warm_pair_learning_rate_scale)) {
    return Status::InvalidArgument("learning_rate_scale and warm_pair_learning_rate_scale must be finite and > 0");
  }
  if (!(o.sw_weight >= 0.0) || !std::isfinite(o.sw_weight)) {
    return Status::InvalidArgument("sw_weight must be finite and >= 0");
  }
  if (!(o.revert_divisor > 1.0)) return Status::InvalidArgument("revert_divisor must be > 1");
  if (!(o.anneal_ratio > 0.0 && o.anneal_ratio <= 1.0)) {
    return Status::InvalidArgument("anneal_ratio must be in (0, 1]");
  }
  if (!(o.plateau_factor > 0.0 && o.plateau_factor <= 1.0)) {
    return Status::InvalidArgument("plateau_factor must be in (0, 1]");
  }
  if (o.stall_iterations < 1) return Status::InvalidArgument("stall_iterations must be >= 1");
  for (const SpectrumWeighting* w : {&o.weighting, &o.warmup_weighting}) {
    if (Status s = ValidateWeighting(*w); !s.ok()) return s;
  }
  if (!(o.final_margin >= 0.0 && o.final_margin < 0.5)) {
    return Status::InvalidArgument("final_margin must be in [0, 0.5)");
  }
  if (!(o.zero_radius >= 0.0 && o.zero_radius <= 16.0)) {
    return Status::InvalidArgument("zero_radius must be in [0, 16]");
  }
  if (!(o.engine_tolerance == 0.0 || (o.engine_tolerance >= 1e-14 && o.engine_tolerance <= 1e-2))) {
    return Status::InvalidArgument("engine_tolerance must be 0 or in [1e-14, 1e-2]");
  }
  if (!(o.warmup_fraction >= 0.0 && o.warmup_fraction < 1.0)) {
    return Status::InvalidArgument("warmup_fraction must be in [0, 1)");
  }
  return Status::Ok();
}

LossTerms EvaluateLoss(const PointSet& points, const std::vector<double>& arbitrary_directions,
                       const FrequencyParams& params, double sw_weight, SpectralEngine& engine,
                       const SpectrumWeighting& weighting) {
  const std::vector<double> dirs = AnisotropyDirections(arbitrary_directions);
  const std::vector<Frequency> k = BuildFrequencySet(params, dirs);
  engine.SetFrequencies(k);
  engine.SetLossWeights(SpectrumLossWeights(k, weighting));
  SpectrumEvaluation eval;
  engine.Evaluate(points, false, &eval);
  SlicedWasserstein sw(static_cast<uint32_t>(points.size()), dirs);
  LossTerms t;
  t.spectrum = eval.loss;
  t.sw = sw.Evaluate(points, nullptr);
  t.total = t.spectrum + sw_weight * t.sw;
  return t;
}
// Everything the loop carries from one iteration to the next, kept between
// slices. `trial`, `scratch` and `sw_grad` are overwritten before they are
// read in every iteration, so they are dropped while the run is paused.
struct OptimizerRun::State {
  OptimizationProblem problem;
  OptimizerOptions options;
  OptimizationResult result;
  std::vector<Frequency> k;
  std::unique_ptr<SlicedWasserstein> sw;
  // The phases: an optional warm-up weighting, then the main one; each ends
  // at its iteration and hands its best set to the next.
  struct Phase {
    std::vector<double> weights;
    int end_iteration;
  };
  std::vector<Phase> phases;
  size_t phase = 0;
  bool phase_started = false;  // `accepted` holds this phase's start
  PointSet x;                  // the set handed to the next phase (or the result)
  AxisStratification stratification;
  double first_lr = 0.0;
  double lr = 0.0;
  double sw_weight = 0.0;
  int max_iterations = 0;
  double anneal_step = 1.0;
  bool started = false;  // the start set is evaluated
  bool over = false;     // finished or cancelled

  AdamState accepted;
  AdamState trial;
  SpectrumEvaluation scratch;
  std::vector<Point2> sw_grad;
  PointSet best;
  LossTerms best_loss;
  double stall_reference = 0.0;
  int since_improvement = 0;
  StopReason reason = StopReason::kMaxIterations;
  int it = 0;

  ProgressInfo Info(int iteration) const {
    ProgressInfo info;
    info.iteration = iteration;
    info.max_iterations = max_iterations;
    info.loss = accepted.loss.total;
    info.spectrum_loss = accepted.loss.spectrum;
    info.sw_loss = accepted.loss.sw;
    info.best_loss = best_loss.total;
    info.learning_rate = lr;
    info.reverts = result.reverts;
    return info;
  }
};

OptimizerRun::OptimizerRun(std::unique_ptr<State> state) : s_(std::move(state)) {}
OptimizerRun::~OptimizerRun() = default;

StatusOr<std::unique_ptr<OptimizerRun>> OptimizerRun::Create(const OptimizationProblem& problem,
                                                             const OptimizerOptions& options) {
  if (Status s = ValidateProblem(problem); !s.ok()) return s;
  if (Status s = ValidateOptions(options); !s.ok()) return s;
  auto st = std::make_unique<State>();
  st->problem = problem;
  st->options = options;
  return std::unique_ptr<OptimizerRun>(new OptimizerRun(std::move(st)));
}

int OptimizerRun::iteration() const { return s_->it; }

size_t OptimizerRun::HeldBytes() const {
  const State& s = *s_;
  const size_t points = s.accepted.x.capacity() + s.accepted.m.capacity() + s.accepted.v.capacity() +
                        s.accepted.grad.capacity() + s.best.capacity() + s.trial.x.capacity() +
                        s.trial.m.capacity() + s.trial.v.capacity() + s.trial.grad.capacity() +
                        s.sw_grad.capacity() + s.scratch.gradient.capacity() + s.x.capacity() +
                        (s.problem.start ? s.problem.start->capacity() : 0);
  size_t weights = 0;
  for (const State::Phase& p : s.phases) weights += p.weights.capacity();
  return points * sizeof(Point2) + s.k.capacity() * sizeof(Frequency) +
         weights * sizeof(double) + s.stratification.HeldBytes() +
         s.scratch.spectrum.capacity() * sizeof(std::complex<double>) +
         (s.sw ? s.sw->directions().size() * s.problem.n * (sizeof(double) + sizeof(uint32_t)) : 0);
}

OptimizerRun::Outcome OptimizerRun::Resume(SpectralEngine& engine, bool engine_holds_k,
                                           const RunCallback& control) {
  State& s = *s_;
  if (s.over) return s.reason == StopReason::kCancelled ? Outcome::kCancelled : Outcome::kFinished;
  const OptimizerOptions& options = s.options;
  const OptimizationProblem& problem = s.problem;
  if (!s.started) {
    s.result.frequency_params = problem.frequency_params.value_or(DefaultFrequencyParams(problem.n));
    if (!problem.frequency_params && problem.directions.size() > 2) {
      s.result.frequency_params = FrequencyParamsForDirections(
          problem.n, static_cast<int>(problem.directions.size()));
    }
    const std::vector<double> dirs = AnisotropyDirections(problem.directions);
    s.k = BuildFrequencySet(s.result.frequency_params, dirs);
    s.result.frequency_count = s.k.size();
    engine.SetTolerance(EffectiveEngineTolerance(options, problem.n));
    engine.SetFrequencies(s.k);
    s.sw = std::make_unique<SlicedWasserstein>(problem.n, dirs);
    s.first_lr = options.learning_rate > 0.0 ? options.learning_rate
                                             : options.learning_rate_scale * DefaultLearningRate(s.k);
    s.lr = s.first_lr;
    s.sw_weight = EffectiveSwWeight(options, problem.n);
    s.max_iterations =
        EffectiveMaxIterations(options, problem.n, static_cast<int>(problem.directions.size()));
    std::vector<double> main_weights =
        SpectrumLossWeights(s.k, options.weighting);
    const int warmup_iterations =
        static_cast<int>(std::lround(options.warmup_fraction * s.max_iterations));
    if (warmup_iterations > 0 && warmup_iterations < s.max_iterations) {
      s.phases.push_back({SpectrumLossWeights(s.k, options.warmup_weighting),
                          warmup_iterations});
    }
    s.phases.push_back({std::move(main_weights), s.max_iterations});
    // `initial` is reported under the main weighting, like `final_loss`.
    s.x = problem.start ? *problem.start : OwenScrambledSobol(problem.n, problem.seed);
    s.problem.start.reset();  // copied into x; not held while paused
    AdamState start;
    engine.SetLossWeights(s.phases.back().weights);
    EvaluateTotal(s.x, engine, *s.sw, s.sw_weight, &s.scratch, &s.sw_grad, &start);
    s.result.initial = start.loss;
    s.anneal_step = std::pow(options.anneal_ratio, 1.0 / s.max_iterations);
    s.started = true;
  } else if (!engine_holds_k) {
    // Everything the engine holds for this run: K, and the weights of the
    // current phase (SetFrequencies resets them), at this run's accuracy.
    engine.SetTolerance(EffectiveEngineTolerance(options, problem.n));
    engine.SetFrequencies(s.k);
    engine.SetLossWeights(s.phases[s.phase].weights);
  }

  AdamState& accepted = s.accepted;
  AdamState& trial = s.trial;
  for (; s.phase < s.phases.size(); ++s.phase, s.phase_started = false) {
    const State::Phase& phase = s.phases[s.phase];
    if (!s.phase_started) {
      engine.SetLossWeights(phase.weights);
      // `accepted` is the state after the last accepted step; each step is
      // tried in `trial`, and the two are swapped when it is accepted (no
      // copies of the O(N) state per iteration).
      accepted = AdamState();
      accepted.x = std::move(s.x);
      accepted.m.assign(problem.n, {0.0, 0.0});
      accepted.v.assign(problem.n, {0.0, 0.0});
      EvaluateTotal(accepted.x, engine, *s.sw, s.sw_weight, &s.scratch, &s.sw_grad, &accepted);
      trial = AdamState();
      s.best = accepted.x;
      s.best_loss = accepted.loss;
      s.stall_reference = s.best_loss.total;
      s.since_improvement = 0;
      s.lr = s.first_lr;
      s.reason = StopReason::kMaxIterations;
      s.phase_started = true;
    }
    while (s.it < phase.end_iteration) {
      const int it = ++s.it;
      s.lr *= s.anneal_step;
      AdamStep(accepted, options, s.lr, &trial);
      if (options.stratify_axes) s.stratification.Apply(&trial.x);
      EvaluateTotal(trial.x, engine, *s.sw, s.sw_weight, &s.scratch, &s.sw_grad, &trial);

      const bool watch_total = options.divergence_signal == DivergenceSignal::kTotalLoss;
      const double now = watch_total ? trial.loss.total : trial.loss.spectrum;
      const double before = watch_total ? accepted.loss.total : accepted.loss.spectrum;
      const bool diverged =
          !std::isfinite(trial.loss.total) || now > (1.0 + options.divergence_threshold) * before;
      if (diverged) {
        s.lr /= options.revert_divisor;
        ++s.result.reverts;
        if (s.lr < options.min_learning_rate) {
          s.reason = StopReason::kLearningRateFloor;
          break;
        }
      } else {
        std::swap(accepted, trial);
        if (accepted.loss.total < s.best_loss.total) {
          s.best_loss = accepted.loss;
          s.best = accepted.x;
        }
        if (s.best_loss.total < (1.0 - options.stall_tolerance) * s.stall_reference) {
          s.stall_reference = s.best_loss.total;
          s.since_improvement = 0;
        } else if (++s.since_improvement >= options.stall_iterations) {
          if (options.plateau_factor >= 1.0) {
            s.reason = StopReason::kStalled;
            break;
          }
          s.lr *= options.plateau_factor;
          s.since_improvement = 0;
          s.stall_reference = s.best_loss.total;
          if (s.lr < options.min_learning_rate) {
            s.reason = StopReason::kStalled;
            break;
          }
        }
      }
      if (options.progress_every > 0 && it % options.progress_every == 0 && control) {
        const RunControl c = control(s.Info(it));
        if (c == RunControl::kCancel) {
          s.reason = StopReason::kCancelled;
          break;
        }
        if (c == RunControl::kPause && it < s.max_iterations) {
          // Drop what the next iteration overwrites anyway.
          trial = AdamState();
          s.scratch = SpectrumEvaluation();
          s.sw_grad = std::vector<Point2>();
          s.stratification.ReleaseScratch();
          return Outcome::kPaused;
        }
      }
    }
    s.x = std::move(s.best);
    s.best = PointSet();
    // A phase that stalls hands over to the next (which then has the rest of
    // the budget); a cancel ends the run.
    if (s.reason == StopReason::kCancelled) break;
    if (s.phase + 1 == s.phases.size() && control) control(s.Info(s.it));
  }
  s.over = true;
  s.result.iterations = s.it;
  if ((options.zero_radius > 0.0 || options.final_margin > 0.0) &&
      s.reason != StopReason::kCancelled) {
    const std::vector<Frequency> low = LowFrequencies(options.zero_radius);
    for (int round = 0; round < 3; ++round) {
      ProjectLowFrequencies(&s.x, low, 2);
      if (options.stratify_axes) s.stratification.Apply(&s.x, options.final_margin);
    }
    ProjectLowFrequencies(&s.x, low, 2);
    AdamState projected;
    EvaluateTotal(s.x, engine, *s.sw, s.sw_weight, &s.scratch, &s.sw_grad, &projected);
    s.best_loss = projected.loss;
  }
  return s.reason == StopReason::kCancelled ? Outcome::kCancelled : Outcome::kFinished;
}

OptimizationResult OptimizerRun::TakeResult() {
  State& s = *s_;
  s.result.points = std::move(s.x);
  s.result.final_loss = s.best_loss;
  s.result.final_learning_rate = s.lr;
  s.result.stop_reason = s.reason;
  return std::move(s.result);
}

StatusOr<OptimizationResult> Optimize(const OptimizationProblem& problem,
                                      const OptimizerOptions& options, SpectralEngine& engine,
                                      const ProgressCallback& progress) {
  auto run = OptimizerRun::Create(problem, options);
  if (!run.ok()) return run.status();
  RunCallback control;
  if (progress) {
    control = [&](const ProgressInfo& p) { return progress(p) ? RunControl::kContinue : RunControl::kCancel; };
  }
  (*run)->Resume(engine, false, control);
  return (*run)->TakeResult();
}

}  // namespace alignset

#include "core/optimize/optimizer.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/optimize/axis_stratification.h"
#include "core/optimize/low_frequency_projection.h"
#include "core/sampling/owen_sobol.h"
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

}  // namespace

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
  o.weighting = {};
  o.warmup_weighting = {};
  o.warmup_fraction = 0.0;
  o.stratify_axes = false;
  o.zero_radius = 0.0;
  o.final_margin = 0.0;
  return o;
}

int DefaultIterationBudget(uint32_t n, int arbitrary_directions) {
  constexpr double kBase = 1000.0;
  constexpr double kBaseN = 4096.0;
  const double per_direction = arbitrary_directions >= 2 ? 1.5 : 1.0;
  return static_cast<int>(
      std::lround(kBase * per_direction * std::sqrt(std::max(1.0, n / kBaseN))));
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
  if (p.directions.empty() || p.directions.size() > 2) {
    return Status::InvalidArgument("expected one or two arbitrary directions, got " +
                                   std::to_string(p.directions.size()));
  }
  for (double d : p.directions) {
    if (!std::isfinite(d)) return Status::InvalidArgument("direction must be a finite angle");
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
  if (!(o.learning_rate >= 0.0) || !std::isfinite(o.learning_rate)) {
    return Status::InvalidArgument("learning_rate must be finite and >= 0");
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

StatusOr<OptimizationResult> Optimize(const OptimizationProblem& problem,
                                      const OptimizerOptions& options, SpectralEngine& engine,
                                      const ProgressCallback& progress) {
  if (Status s = ValidateProblem(problem); !s.ok()) return s;
  if (Status s = ValidateOptions(options); !s.ok()) return s;

  OptimizationResult result;
  result.frequency_params = problem.frequency_params.value_or(DefaultFrequencyParams(problem.n));
  const std::vector<double> dirs = AnisotropyDirections(problem.directions);
  const std::vector<Frequency> k = BuildFrequencySet(result.frequency_params, dirs);
  result.frequency_count = k.size();
  engine.SetFrequencies(k);
  const SlicedWasserstein sw(problem.n, dirs);

  const double first_lr =
      options.learning_rate > 0.0 ? options.learning_rate : DefaultLearningRate(k);
  const double sw_weight = EffectiveSwWeight(options, problem.n);
  const int max_iterations = EffectiveMaxIterations(
      options, problem.n, static_cast<int>(problem.directions.size()));

  // The phases: an optional warm-up weighting, then the main one.
  struct Phase {
    std::vector<double> weights;
    int end_iteration;
  };
  std::vector<Phase> phases;
  const std::vector<double> main_weights =
      SpectrumLossWeights(k, options.weighting);
  const int warmup_iterations =
      static_cast<int>(std::lround(options.warmup_fraction * max_iterations));
  if (warmup_iterations > 0 && warmup_iterations < max_iterations) {
    phases.push_back({SpectrumLossWeights(k, options.warmup_weighting),
                      warmup_iterations});
  }
  phases.push_back({main_weights, max_iterations});

  SpectrumEvaluation scratch;
  std::vector<Point2> sw_grad;
  // `initial` is reported under the main weighting, like `final_loss`.
  PointSet x = problem.start ? *problem.start : OwenScrambledSobol(problem.n, problem.seed);
  {
    AdamState start;
    engine.SetLossWeights(main_weights);
    EvaluateTotal(x, engine, sw, sw_weight, &scratch, &sw_grad, &start);
    result.initial = start.loss;
  }

  AxisStratification stratification;
  StopReason reason = StopReason::kMaxIterations;
  double lr = first_lr;
  LossTerms best_loss;
  int it = 0;
  for (const Phase& phase : phases) {
    engine.SetLossWeights(phase.weights);
    // `accepted` is the state after the last accepted step; each step is
    // tried in `trial`, and the two are swapped when it is accepted (no
    // copies of the O(N) state per iteration).
    AdamState accepted;
    accepted.x = std::move(x);
    accepted.m.assign(problem.n, {0.0, 0.0});
    accepted.v.assign(problem.n, {0.0, 0.0});
    EvaluateTotal(accepted.x, engine, sw, sw_weight, &scratch, &sw_grad, &accepted);
    AdamState trial;
    PointSet best = accepted.x;
    best_loss = accepted.loss;
    double stall_reference = best_loss.total;
    int since_improvement = 0;
    lr = first_lr;
    reason = StopReason::kMaxIterations;

    auto report = [&](int iteration) {
      if (!progress) return true;
      ProgressInfo info;
      info.iteration = iteration;
      info.max_iterations = max_iterations;
      info.loss = accepted.loss.total;
      info.spectrum_loss = accepted.loss.spectrum;
      info.sw_loss = accepted.loss.sw;
      info.best_loss = best_loss.total;
      info.learning_rate = lr;
      info.reverts = result.reverts;
      return progress(info);
    };

    const double anneal_step = std::pow(options.anneal_ratio, 1.0 / max_iterations);
    while (it < phase.end_iteration) {
      ++it;
      lr *= anneal_step;
      AdamStep(accepted, options, lr, &trial);
      if (options.stratify_axes) stratification.Apply(&trial.x);
      EvaluateTotal(trial.x, engine, sw, sw_weight, &scratch, &sw_grad, &trial);

      const bool watch_total = options.divergence_signal == DivergenceSignal::kTotalLoss;
      const double now = watch_total ? trial.loss.total : trial.loss.spectrum;
      const double before = watch_total ? accepted.loss.total : accepted.loss.spectrum;
      const bool diverged =
          !std::isfinite(trial.loss.total) || now > (1.0 + options.divergence_threshold) * before;
      if (diverged) {
        lr /= options.revert_divisor;
        ++result.reverts;
        if (lr < options.min_learning_rate) {
          reason = StopReason::kLearningRateFloor;
          break;
        }
      } else {
        std::swap(accepted, trial);
        if (accepted.loss.total < best_loss.total) {
          best_loss = accepted.loss;
          best = accepted.x;
        }
        if (best_loss.total < (1.0 - options.stall_tolerance) * stall_reference) {
          stall_reference = best_loss.total;
          since_improvement = 0;
        } else if (++since_improvement >= options.stall_iterations) {
          if (options.plateau_factor >= 1.0) {
            reason = StopReason::kStalled;
            break;
          }
          lr *= options.plateau_factor;
          since_improvement = 0;
          stall_reference = best_loss.total;
          if (lr < options.min_learning_rate) {
            reason = StopReason::kStalled;
            break;
          }
        }
      }
      if (options.progress_every > 0 && it % options.progress_every == 0 && !report(it)) {
        reason = StopReason::kCancelled;
        break;
      }
    }
    x = std::move(best);
    // A phase that stalls hands over to the next (which then has the rest of
    // the budget); a cancel ends the run.
    if (reason == StopReason::kCancelled) break;
    if (&phase == &phases.back()) report(it);
  }
  result.iterations = it;
  if ((options.zero_radius > 0.0 || options.final_margin > 0.0) &&
      reason != StopReason::kCancelled) {
    const std::vector<Frequency> low = LowFrequencies(options.zero_radius);
    for (int round = 0; round < 3; ++round) {
      ProjectLowFrequencies(&x, low, 2);
      if (options.stratify_axes) stratification.Apply(&x, options.final_margin);
    }
    ProjectLowFrequencies(&x, low, 2);
    AdamState projected;
    EvaluateTotal(x, engine, sw, sw_weight, &scratch, &sw_grad, &projected);
    best_loss = projected.loss;
  }
  result.points = std::move(x);
  result.final_loss = best_loss;
  result.final_learning_rate = lr;
  result.stop_reason = reason;
  return result;
}

}  // namespace alignset

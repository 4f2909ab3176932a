#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/optimize/spectrum_weights.h"
#include "core/spectral/direction_budget.h"
#include "core/spectral/frequency_set.h"
#include "core/util/point_set.h"
#include "core/spectral/spectral_engine.h"
#include "core/util/status.h"

namespace alignset {

// Smallest and largest point counts the core accepts. Below 16 there is no
// meaningful frequency set; above 2^20 a single set would not fit the
// service's messages.
inline constexpr uint32_t kMinPoints = 16;
inline constexpr uint32_t kMaxPoints = 1u << 20;

// What to make: N points whose spectrum is dark along 0°, 90° and the 1 to
// kMaxArbitraryDirections (8) arbitrary directions (degrees, spectral
// convention: the edge normal). One or two are the service's canonical
// spaces; more are made locally only (docs/results.md, "Any number of
// directions").
struct OptimizationProblem {
  uint32_t n = 0;
  std::vector<double> directions;
  uint64_t seed = 1;
  // Unset: DefaultFrequencyParams(n) for one or two directions,
  // FrequencyParamsForDirections(n, k) for more (direction_budget.h).
  std::optional<FrequencyParams> frequency_params;
  // Unset: Owen-scrambled Sobol from `seed`. Set: continue from these n
  // points (in [0,1)^2).
  std::optional<PointSet> start;
};

// Which loss the revert-and-divide rule watches.
enum class DivergenceSignal {
  kSpectrumLoss,  // alignset's default, see OptimizerOptions
  kTotalLoss,     // the literal rule; kept to measure why it is not the default
};

struct OptimizerOptions {
  // The iteration budget; 0 selects DefaultIterationBudget(N).
  int max_iterations = 0;
  // First Adam step size. 0 picks learning_rate_scale * DefaultLearningRate()
  // from K.
  double learning_rate = 0.0;
  double learning_rate_scale = 1.0;
  // Total loss L = L_Spec + c * L_SW with c = sw_weight; 0 selects c = 4N.
  //
  // The supplement's c = 10 belongs to its own normalization of L_SW, which
  // the seeds do not give. With L_SW as a mean over points the SW gradient on
  // a point shrinks like 1/N against the spectral one, so c must grow with N
  // or the low frequencies stay under-stratified; c = 4N reaches c = N's
  // converged quality sooner, because the variance is decided by the lowest
  // frequencies along θ, which the SW term stratifies directly (the figures:
  // docs/method.md, "SW weight c = 4N"). sw_weight = 10 reproduces the
  // literal reading.
  double sw_weight = 0.0;
  // The low-frequency levers (docs/method.md, "The low-frequency floor").
  // The supplement's flat mean over K leaves every frequency of K at about
  // the loss value, so the handful of lowest frequencies, which decide the
  // variance of smooth integrands and most of an edge's, sit at ~1e-3 where
  // Owen-Sobol has 1e-5. SupplementOptimizerOptions() turns all of them off.
  //
  // Weights of the spectrum loss over K (spectrum_weights.h): (r_min/|v|)^2.5
  // in the main phase.
  SpectrumWeighting weighting{2.5};
  // A first phase: `warmup_fraction` of the iteration budget with
  // `warmup_weighting`; then the best set of that phase is optimized further
  // with `weighting`, the Adam moments, learning rate and plateau rule
  // restarted. 0 runs `weighting` alone. The gentler exponent first spreads
  // the effort over the strips (the aligned edge), the steeper one then
  // drives the lowest frequencies down.
  SpectrumWeighting warmup_weighting{1.5};
  double warmup_fraction = 0.7;
  // Clamp every step onto the sets stratified along both axes
  // (axis_stratification.h): one point per column and row of width 1/N, the
  // (0,2)-like structure of the Owen-Sobol start kept, which the axis edges
  // and separable integrands need.
  bool stratify_axes = true;
  // After the last phase, the best set is projected onto F(v) = 0 for
  // 0 < |v| <= zero_radius (low_frequency_projection.h), alternating with
  // the axis clamp when stratify_axes is on. 0: no projection.
  double zero_radius = 3.0;
  // The final clamp keeps each axis coordinate within the central
  // 1 - 2 margin of its stratum (0: anywhere in it); points near the centre
  // of their column lower the axis-edge variance about 2x.
  double final_margin = 0.4;
  // The accuracy the optimizer asks of its engine (SpectralEngine::
  // SetTolerance) for the descent; 0 selects DefaultEngineTolerance(N).
  double engine_tolerance = 0.0;
  double beta1 = 0.9;
  double beta2 = 0.999;
  double epsilon = 1e-12;
  // The revert-and-divide rule: a step whose *spectrum* loss rises by more
  // than this fraction over the last accepted state is undone and the
  // learning rate divided by `revert_divisor`. The SW term is left out of the
  // trigger on purpose: it jumps whenever a point wraps across the torus edge,
  // and treating that as divergence collapses the learning rate.
  double divergence_threshold = 0.10;
  DivergenceSignal divergence_signal = DivergenceSignal::kSpectrumLoss;
  double revert_divisor = 10.0;
  // Plateau rule: when the best total loss has not improved by
  // `stall_tolerance` (relative) over `stall_iterations` accepted steps, the
  // learning rate is multiplied by `plateau_factor`; with factor 1 (or
  // below the floor) the run stops as stalled.
  int stall_iterations = 200;
  double stall_tolerance = 1e-3;
  double plateau_factor = 0.5;
  // Annealing: the learning rate is multiplied every iteration by the factor
  // that takes it to `anneal_ratio` times its start at `max_iterations` (on
  // top of the revert and plateau rules). 1 keeps it constant.
  double anneal_ratio = 1.0;
  // The run stops once the learning rate falls below this.
  double min_learning_rate = 1e-7;
  // Call the progress callback every this many iterations (and at the end).
  int progress_every = 10;
  // The budget of a warm-started descent (WarmStartOptions), as a fraction
  // of the cold budget. The service starts every key that is not a root of
  // the key lineage (core/align/key_lineage.h) from its parent's set; 0
  // optimizes every key from Owen-Sobol. 0.13: 130 iterations for one
  // direction and 195 for two at N = 4096. The warm options below were each
  // measured against the cold sets of the same seeds; the figures are in
  // docs/method.md, "Filling the space: the key lineage", and
  // docs/results.md, "Filling the space".
  double warm_budget_fraction = 0.13;
  // The share of a warm descent run with `warmup_weighting` before the
  // main weighting, as in a cold one: the main weighting alone lets the
  // aligned edge and the smoothed step drift from the cold sets' along a
  // chain.
  double warm_warmup_fraction = 0.5;
  // The first step of a two-direction warm descent, as a multiple of the
  // default (learning_rate_scale): the cold descent's first step cost the
  // Gaussians against the cold set, and both half and three times this one
  // cost more (a narrow range, measured at N = 4096 only, whose cause was
  // not isolated). One-direction warm descents keep the cold step. Only up
  // to warm_pair_learning_rate_max_points: above, it was screened only, and
  // at 65536 it made one-direction warm sets worse.
  double warm_pair_learning_rate_scale = 2.0;
  uint32_t warm_pair_learning_rate_max_points = 4096;
  // The largest N whose warm descents run that warm-up share; above it the
  // whole warm budget runs the main weighting (algorithm version 8): at
  // 65536 the warm-up half lets the lowest frequencies drift and the main
  // iterations left do not bring them back, while at 16384 and 32768 the
  // aligned edge needs the half.
  uint32_t warm_warmup_max_points = 32768;
  // The smallest N whose keys use the lineage. Below it every key is
  // optimized from Owen-Sobol: a cold fill is cheap there, and the warm sets
  // were further from the cold ones.
  uint32_t warm_min_points = 4096;
};

// True when the service starts keys of N points from their lineage parent
// (warm_budget_fraction > 0 and N >= warm_min_points).
bool UsesKeyLineage(const OptimizerOptions& options, uint32_t n);

// alignset's profile before the low-frequency levers (algorithm version 2):
// the supplement's flat spectrum loss, no warm-up, no axis clamp, no
// projection. Used by the benchmarks that compare the two.
OptimizerOptions SupplementOptimizerOptions();
// Turns the low-frequency levers off and asks the engine for its full
// accuracy again, and leaves every other option as it is: the supplement's
// profile (algorithm version 2) with a caller's budget, seed and schedule.
void TurnOffLowFrequencyLevers(OptimizerOptions* options);

// The weight c of L_SW that `options` selects for N points.
double EffectiveSwWeight(const OptimizerOptions& options, uint32_t n);

// The iteration budget alignset uses for N points and one or two arbitrary
// directions: 1000 up to N = 4096, then growing like sqrt(N) (2000 at 16384,
// 4000 at 65536), and half as much again for two arbitrary directions.
// That many iterations bring the aligned step-edge variance within a few
// percent of a fully converged set; larger sets need more because their
// lowest frequencies span more point spacings, and two-direction sets have
// five strips to darken (docs/method.md, "Schedule"; docs/results.md,
// "Engines").
int DefaultIterationBudget(uint32_t n, int arbitrary_directions = 1);

// The options of a descent that continues from a neighbouring key's set:
// `cold`'s budget times warm_budget_fraction (at least one iteration), of
// which warm_warmup_fraction with the warm-up weighting (none above
// warm_warmup_max_points), for two directions up to
// warm_pair_learning_rate_max_points a first step warm_pair_learning_rate_scale
// times the default, the rest as in `cold`. The start is converged
// already, so a short descent moves the strips by the step between the keys.
OptimizerOptions WarmStartOptions(const OptimizerOptions& cold, uint32_t n,
                                  int arbitrary_directions);

// The budget `options` selects for the problem.
int EffectiveMaxIterations(const OptimizerOptions& options, uint32_t n,
                           int arbitrary_directions = 1);

// The engine accuracy alignset's descent asks for: 1e-7 up to N = 4096, the
// fast engine's full 1e-11 above. A descent needs less than an analysis:
// up to 4096 the looser descent ends where the full one does (within seed
// noise on the whole integrand family) and is faster (width 8 fills two
// AVX2 vectors per kernel row). Above 4096, F's absolute error (~ tolerance
// N) nears the lowest frequencies' own size, and looser descents took other
// paths (the figures: docs/method.md, "The low-frequency floor").
double DefaultEngineTolerance(uint32_t n);

// The tolerance `options` selects for N points.
double EffectiveEngineTolerance(const OptimizerOptions& options, uint32_t n);

// The first step size, scaled to the highest suppressed frequency: a step of
// lr moves the phase at frequency |v| by 2 pi |v| lr, so lr ~ 1 / |v|max keeps
// the largest phase change per step a fixed fraction of a cycle.
double DefaultLearningRate(const std::vector<Frequency>& k);

enum class StopReason { kMaxIterations, kStalled, kLearningRateFloor, kCancelled };
std::string StopReasonName(StopReason r);

struct ProgressInfo {
  int iteration = 0;
  int max_iterations = 0;
  double loss = 0.0;
  double spectrum_loss = 0.0;
  double sw_loss = 0.0;
  double best_loss = 0.0;
  double learning_rate = 0.0;
  int reverts = 0;
};

// Returning false cancels the optimization (the best set so far is kept).
using ProgressCallback = std::function<bool(const ProgressInfo&)>;

struct LossTerms {
  double total = 0.0;
  double spectrum = 0.0;
  double sw = 0.0;
};

struct OptimizationResult {
  PointSet points;          // the best set seen, in [0,1)^2
  LossTerms initial;        // at the Owen-Sobol start
  LossTerms final_loss;     // of `points`
  FrequencyParams frequency_params;
  size_t frequency_count = 0;
  int iterations = 0;
  int reverts = 0;
  double final_learning_rate = 0.0;
  StopReason stop_reason = StopReason::kMaxIterations;
};

// Checks a problem at the boundary: N in [kMinPoints, kMaxPoints], 1 to
// kMaxArbitraryDirections finite directions (with three or more, all of them
// and the axes distinct modulo 180°), valid frequency parameters. One or two
// directions may repeat each other or an axis: the service's two-direction
// space has its repeated pairs (30°, 30°) as keys of their own.
Status ValidateProblem(const OptimizationProblem& problem);
Status ValidateOptions(const OptimizerOptions& options);

// Optimizes the set by Adam on L_Spec + c L_SW from Owen-scrambled Sobol.
// Deterministic for a given problem and options (the engines' sums do not
// depend on the thread count).
StatusOr<OptimizationResult> Optimize(const OptimizationProblem& problem,
                                      const OptimizerOptions& options, SpectralEngine& engine,
                                      const ProgressCallback& progress = nullptr);

// What a resumable run's callback asks for after a progress report.
enum class RunControl { kContinue, kPause, kCancel };
using RunCallback = std::function<RunControl(const ProgressInfo&)>;

// Optimize() in slices: a run stops between two iterations when its callback
// asks to pause, holds its whole loop state (the Adam state, the best set,
// the schedule's counters), and goes on later, on the same engine or another
// one, ending with bit for bit the set that one uninterrupted Optimize()
// gives (the engines' results depend only on K and the points). The server
// uses it to share its workers between clients: a long optimization yields
// its worker to someone else's short one and resumes afterwards.
class OptimizerRun {
 public:
  enum class Outcome { kFinished, kPaused, kCancelled };

  // Validates the problem and options; allocates nothing large yet.
  static StatusOr<std::unique_ptr<OptimizerRun>> Create(const OptimizationProblem& problem,
                                                        const OptimizerOptions& options);
  ~OptimizerRun();

  // Runs from where the last slice stopped until the run finishes or
  // `control` (called every options.progress_every iterations, and once at
  // the end, whose answer is then ignored) asks to pause or cancel.
  // `engine_holds_k`: nothing else ran on `engine` since this run's last
  // slice, so its frequency set is still this run's; otherwise it is set
  // again.
  Outcome Resume(SpectralEngine& engine, bool engine_holds_k, const RunCallback& control);

  int iteration() const;
  // What the run holds between slices (state, best set, K), in bytes.
  size_t HeldBytes() const;
  // After kFinished or kCancelled: the best set so far and its figures.
  OptimizationResult TakeResult();

 private:
  struct State;
  explicit OptimizerRun(std::unique_ptr<State> state);
  std::unique_ptr<State> s_;
};

// INVALID_ARGUMENT naming the first direction that repeats another or an
// axis (modulo 180°).
Status CheckDistinctDirections(const std::vector<double>& arbitrary);

// L_Spec, L_SW and the total of a given set (no gradient), for reporting.
LossTerms EvaluateLoss(const PointSet& points, const std::vector<double>& arbitrary_directions,
                       const FrequencyParams& params, double sw_weight, SpectralEngine& engine,
                       const SpectrumWeighting& weighting = {});

}  // namespace alignset

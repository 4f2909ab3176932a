#include <alignset/aligned_sampler.h>

#include <alignset/pixel_shift.h>

#include <algorithm>
#include <array>
#include <cmath>

#include "core/optimize/aligned_lattice.h"
#include "core/optimize/construction.h"
#include "core/sampling/owen_sobol.h"
#include "core/util/hash.h"

namespace alignset {
namespace {

// The salts of the pixel's randomizations: alignset render's (render/), so
// the library and the renderer draw the same points.
constexpr uint64_t kSaltSet = 1;
constexpr uint64_t kSaltShift = 2;

uint64_t PixelHash(uint64_t seed, uint32_t x, uint32_t y, uint64_t salt) {
  return HashCombine(HashCombine(HashCombine(seed, salt), static_cast<uint64_t>(x)), static_cast<uint64_t>(y));
}

double Mean(std::span<const double> v) {
  double s = 0.0;
  for (double x : v) s += x;
  return v.empty() ? 0.0 : s / static_cast<double>(v.size());
}

}  // namespace

StatusOr<AlignedSampler> AlignedSampler::Create(std::shared_ptr<const SetTable> table,
                                                const AlignedSamplerOptions& options) {
  if (!table) return Status::InvalidArgument("no table");
  const Construction* construction = FindConstruction(options.construction);
  if (construction == nullptr || options.construction.empty()) {
    return Status::InvalidArgument("unknown construction '" + options.construction + "': the known ones are " +
                                   KnownConstructionNames());
  }
  if (options.stack_radius < 0) {
    return Status::InvalidArgument("stack_radius must be 0 (auto) or in [1, 4], got " +
                                   std::to_string(options.stack_radius));
  }
  // The construction's own name (static), not the options' string: the
  // sections outlive any copy of the options.
  const SetTable::Sections sections = table->Resolve(options.n, construction->name);
  if (!sections.one_direction()) {
    std::string have;
    for (uint32_t n : table->PointCounts(options.construction)) have += (have.empty() ? "" : ", ") + std::to_string(n);
    return Status::NotFound("the table has no one-direction " + options.construction + " sets of N = " +
                            std::to_string(options.n) + " (it has " +
                            (have.empty() ? std::string("none of that construction") : "N = " + have) + ")");
  }
  const bool shared = options.domain == PixelDomain::kShared;
  PrepassFitOptions fo;
  fo.domain = options.domain;
  fo.image_width = options.image_width;
  fo.seed = options.seed;
  fo.prepass_samples = options.prepass_samples != 0 ? options.prepass_samples
                                                    : std::clamp<uint32_t>(options.n / 4, 16, 256);
  fo.stack_radius = options.stack_radius != 0 ? options.stack_radius : options.n <= 1024 ? 2 : 1;
  switch (options.prepass_points) {
    case AlignedSamplerOptions::PrepassPoints::kAuto: fo.lattice_points = options.n <= 1024 || shared; break;
    case AlignedSamplerOptions::PrepassPoints::kLattice: fo.lattice_points = true; break;
    case AlignedSamplerOptions::PrepassPoints::kOwenSobol: fo.lattice_points = false; break;
  }
  auto fit = PrepassFit::Create(fo);
  if (!fit.ok()) return fit.status();
  AlignedSampler s;
  // A point set's one-direction alignments are made here, once per table,
  // so that no pixel allocates one.
  table->AlignOneDirectionSets(sections);
  s.table_ = std::move(table);
  s.sections_ = sections;
  s.options_ = options;
  s.fit_ = *fit;
  s.weight_ = ::alignset::PrepassWeight(fo.prepass_samples, options.n);
  s.progressive_ = construction->progressive();
  return s;
}

void AlignedSampler::PrepassPoints(uint32_t x, uint32_t y, std::span<Point2> out) const {
  fit_.PrepassPoints(x, y, out);
}

StatusOr<PixelPlan> AlignedSampler::Plan(uint32_t x, uint32_t y, std::span<const std::span<const double>> block,
                                         Scratch& scratch) const {
  auto fitted = fit_.Fit(x, y, block, scratch.fit_);
  if (!fitted.ok()) return fitted.status();
  Scratch::Stats& stats = scratch.stats_;
  stats.fit_refused += fitted->own_refused + fitted->pooled_refused;
  const FittedDirections& d = *fitted;
  PixelPlan plan;
  plan.x = x;
  plan.y = y;
  plan.directions = d.directions;
  plan.theta1_deg = d.theta1_deg;
  plan.theta2_deg = d.theta2_deg;
  AlignedPolicy policy;
  policy.two_directions = options_.two_directions;
  plan.choice = ChooseSet({d.directions, d.theta1_deg, d.theta2_deg}, policy);
  ++stats.pixels;
  if (plan.choice.kind == SetChoice::Kind::kFallback) {
    const bool continued = options_.reuse == PrepassReuse::kContinue && !lattice_prepass();
    plan.main = continued ? PixelPlan::Main::kContinued : PixelPlan::Main::kOwenSobol;
    plan.main_seed = continued ? fit_.PrepassSeed(x, y) : PixelHash(options_.seed, x, y, kSaltSet);
    return plan;
  }
  ++stats.with_direction;
  if (plan.choice.kind == SetChoice::Kind::kTwo && !table_->Holds(sections_, plan.choice)) {
    // A table without two-direction sets, or without this pair: the
    // stronger edge's set (documented; asked before any lookup, so no
    // error is built).
    AlignedPolicy one = policy;
    one.two_directions = false;
    plan.choice = ChooseSet({d.directions, d.theta1_deg, d.theta2_deg}, one);
    plan.pair_fell_back = true;
    ++stats.pair_fell_back;
  }
  auto set = table_->Find(sections_, plan.choice);
  if (!set.ok()) return set.status();
  if (plan.choice.kind == SetChoice::Kind::kTwo) ++stats.two_directions;
  plan.set = *set;
  plan.main = PixelPlan::Main::kSet;
  plan.shift = PixelShift(HashCombine(options_.seed, kSaltShift), x, y);
  return plan;
}

void SetPixelPoints(const TableSet& set, Point2 shift, std::span<Point2> out) {
  if (set.lattice_generator != 0) {
    // The lattice's realization 0 under the pixel's shift (the points
    // alignset render's lattices take), folded after the shift for a
    // tent-lattice.
    Rank1LatticePointsInto(set.n, set.lattice_generator, 0, out);
    const double below_one = std::nextafter(1.0, 0.0);
    for (Point2& p : out) {
      p = ShiftPoint(p, shift);
      if (set.folded) p = {std::min(TentFold(p.x), below_one), std::min(TentFold(p.y), below_one)};
    }
    return;
  }
  const size_t count = std::min(out.size(), set.points->size());
  for (size_t i = 0; i < count; ++i) out[i] = ShiftPoint((*set.points)[i], shift);
}

void FallbackPixelPoints(uint64_t seed, uint32_t x, uint32_t y, std::span<Point2> out) {
  OwenScrambledSobolInto(PixelHash(seed, x, y, kSaltSet), 0, out);
}

void AlignedSampler::MainPoints(const PixelPlan& plan, std::span<Point2> out) const {
  const std::span<Point2> points = out.first(std::min<size_t>(out.size(), options_.n));
  switch (plan.main) {
    case PixelPlan::Main::kOwenSobol:
      OwenScrambledSobolInto(plan.main_seed, 0, points);
      return;
    case PixelPlan::Main::kContinued:
      OwenScrambledSobolInto(plan.main_seed, prepass_samples(), points);
      return;
    case PixelPlan::Main::kSet:
      SetPixelPoints(plan.set, plan.shift, points);
      return;
  }
}

double AlignedSampler::Estimate(const PixelPlan& plan, std::span<const double> prepass_values,
                                std::span<const double> main_values) const {
  const double pre = Mean(prepass_values), main = Mean(main_values);
  if (options_.reuse == PrepassReuse::kUnbiased || plan.main == PixelPlan::Main::kSet) {
    // A prefix of the main points (a pixel that stopped early) weighs the
    // pre-pass as beside that many.
    const double w = main_values.size() == options_.n
                         ? weight_
                         : alignset::PrepassWeight(prepass_samples(), static_cast<uint32_t>(main_values.size()));
    return w * pre + (1.0 - w) * main;
  }
  if (plan.main == PixelPlan::Main::kOwenSobol) return main;  // after a lattice pre-pass: no sequence to continue
  return ContinuedEstimate(pre, static_cast<uint32_t>(prepass_values.size()), main_values);
}

double PrepassWeight(uint32_t prepass_samples, uint32_t n) {
  if (prepass_samples == 0) return 0.0;
  const double p = std::pow(static_cast<double>(prepass_samples), 1.5);
  return p / (p + 2.0 * std::pow(static_cast<double>(n), 1.5));
}

double ContinuedEstimate(double prepass_mean, uint32_t prepass_samples, std::span<const double> continued_values) {
  // The pre-pass lies in the first block (its values enter by their sum).
  const uint32_t m = prepass_samples, total = m + static_cast<uint32_t>(continued_values.size());
  std::array<uint32_t, 32> blocks{};  // largest first (no allocation per pixel)
  size_t count = 0;
  for (uint32_t bit = 1u << 31; bit != 0; bit >>= 1) {
    if (total & bit) blocks[count++] = bit;
  }
  if (count == 0) return prepass_mean;
  if (m > blocks[0]) {  // the pre-pass spans blocks: a plain mean of every point
    blocks[0] = total;
    count = 1;
  }
  double estimate = 0.0, weights = 0.0;
  uint32_t begin = 0;
  for (size_t b = 0; b < count; ++b) {
    const uint32_t size = blocks[b];
    double sum = begin == 0 ? static_cast<double>(m) * prepass_mean : 0.0;
    for (uint32_t k = std::max(begin, m); k < begin + size; ++k) sum += continued_values[k - m];
    const double w = std::pow(static_cast<double>(size), 3.0);
    estimate += w * sum / size;
    weights += w;
    begin += size;
  }
  return estimate / weights;
}

}  // namespace alignset

#include <alignset/aligned_sampler.h>

#include <alignset/pixel_shift.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "core/analysis/edge_line_fit.h"
#include "core/optimize/aligned_lattice.h"
#include "core/optimize/construction.h"
#include "core/sampling/owen_sobol.h"
#include "core/sampling/rank1_lattice.h"
#include "core/util/directions.h"
#include "core/util/hash.h"

namespace alignset {
namespace {

// The salts of the pixel's randomizations: alignset render's (render/), so
// the library and the renderer draw the same points.
constexpr uint64_t kSaltSet = 1;
constexpr uint64_t kSaltShift = 2;
constexpr uint64_t kSaltPrepassLattice = 0x6c61747469636501ull;

// The edge-line fit's settings of record (docs/rendering.md, "Every sample
// counted"): a second line needs 15% of the crossings (a corner's shorter
// edge, pooled or stacked, still holds many); the stacked fit draws 24
// candidate lines (a block of 9 or 25 pixels supports each amply); a pooled
// footprint reads the samples within half a pixel; and where the pixel's own
// fit and the pooled one disagree by more than 8 degrees on footprints, the
// pixel's own stands.
constexpr double kSecondLineShare = 0.15;
constexpr int kStackedCandidates = 24;
constexpr double kPooledMargin = 0.5;
constexpr double kAgreeDeg = 8.0;
constexpr uint32_t kMaxPrepass = 4096;

uint64_t PixelHash(uint64_t seed, uint32_t x, uint32_t y, uint64_t salt) {
  return HashCombine(HashCombine(HashCombine(seed, salt), static_cast<uint64_t>(x)), static_cast<uint64_t>(y));
}

Point2 HashShift(uint64_t h) {
  return {static_cast<double>(h >> 11) * 0x1.0p-53, static_cast<double>(Mix64(h) >> 11) * 0x1.0p-53};
}

double Wrap(double u) { return u >= 1.0 ? u - 1.0 : u; }

double Mean(std::span<const double> v) {
  double s = 0.0;
  for (double x : v) s += x;
  return v.empty() ? 0.0 : s / static_cast<double>(v.size());
}

EdgeLineOptions LineOptions() {
  EdgeLineOptions o;
  o.second = true;
  o.second_min_share = kSecondLineShare;
  return o;
}

EdgeLineOptions StackedOptions() {
  EdgeLineOptions o = LineOptions();
  o.candidates = kStackedCandidates;
  return o;
}

struct Found {
  int directions = 0;
  double theta1 = 0.0, theta2 = 0.0;
};

Found FromEstimate(const DirectionEstimate& e) {
  Found f;
  if (e.first.status != DirectionStatus::kFound) return f;
  f.directions = 1;
  f.theta1 = e.first.theta_deg;
  if (e.has_second && e.second.status == DirectionStatus::kFound) {
    f.directions = 2;
    f.theta2 = e.second.theta_deg;
  }
  return f;
}

}  // namespace

struct AlignedSampler::Scratch::Impl {
  std::vector<SampledPatch> patches;     // the block's pre-passes
  std::vector<PatchCrossings> crossings; // stacked: each pixel's crossings
  std::vector<const PatchCrossings*> stacked;
  Stats stats;
};

AlignedSampler::Scratch::Scratch() : impl_(std::make_unique<Impl>()) {}
AlignedSampler::Scratch::~Scratch() = default;
AlignedSampler::Scratch::Scratch(Scratch&&) noexcept = default;
AlignedSampler::Scratch& AlignedSampler::Scratch::operator=(Scratch&&) noexcept = default;
const AlignedSampler::Scratch::Stats& AlignedSampler::Scratch::stats() const { return impl_->stats; }

StatusOr<AlignedSampler> AlignedSampler::Create(std::shared_ptr<const SetTable> table,
                                                const AlignedSamplerOptions& options) {
  if (!table) return Status::InvalidArgument("no table");
  const Construction* construction = FindConstruction(options.construction);
  if (construction == nullptr || options.construction.empty()) {
    return Status::InvalidArgument("unknown construction '" + options.construction + "': the known ones are " +
                                   KnownConstructionNames());
  }
  if (options.image_width == 0) return Status::InvalidArgument("image_width must be at least 1");
  if (options.prepass_samples != 0 && (options.prepass_samples < 16 || options.prepass_samples > kMaxPrepass)) {
    return Status::InvalidArgument("prepass_samples must be 0 (auto) or in [16, " + std::to_string(kMaxPrepass) +
                                   "], got " + std::to_string(options.prepass_samples));
  }
  if (options.stack_radius < 0 || options.stack_radius > 4) {
    return Status::InvalidArgument("stack_radius must be 0 (auto) or in [1, 4], got " +
                                   std::to_string(options.stack_radius));
  }
  if (!table->Has(options.n, options.construction, TableSpace::kOneDirection) &&
      !table->Has(options.n, options.construction, TableSpace::kOneQuarter)) {
    std::string have;
    for (uint32_t n : table->PointCounts(options.construction)) have += (have.empty() ? "" : ", ") + std::to_string(n);
    return Status::NotFound("the table has no one-direction " + options.construction + " sets of N = " +
                            std::to_string(options.n) + " (it has " +
                            (have.empty() ? std::string("none of that construction") : "N = " + have) + ")");
  }
  AlignedSampler s;
  s.table_ = std::move(table);
  s.options_ = options;
  s.prepass_ = options.prepass_samples != 0 ? options.prepass_samples : std::clamp<uint32_t>(options.n / 4, 16, 256);
  const bool shared = options.domain == PixelDomain::kShared;
  s.radius_ = !shared ? 1 : options.stack_radius != 0 ? options.stack_radius : options.n <= 1024 ? 2 : 1;
  switch (options.prepass_points) {
    case AlignedSamplerOptions::PrepassPoints::kAuto: s.lattice_prepass_ = options.n <= 1024 || shared; break;
    case AlignedSamplerOptions::PrepassPoints::kLattice: s.lattice_prepass_ = true; break;
    case AlignedSamplerOptions::PrepassPoints::kOwenSobol: s.lattice_prepass_ = false; break;
  }
  const double p = std::pow(static_cast<double>(s.prepass_), 1.5);
  s.weight_ = p / (p + 2.0 * std::pow(static_cast<double>(options.n), 1.5));
  return s;
}

void AlignedSampler::PrepassPoints(uint32_t x, uint32_t y, std::span<Point2> out) const {
  const uint64_t h = HashCombine(options_.seed, static_cast<uint64_t>(y) * options_.image_width + x);
  const uint32_t m = static_cast<uint32_t>(std::min<size_t>(out.size(), prepass_));
  if (!lattice_prepass_) {
    OwenScrambledSobolInto(h, 0, out.first(m));
    return;
  }
  // A rank-1 lattice of M points under a uniform shift: unbiased, and its
  // samples lie more evenly than Owen-Sobol's, so an edge's crossings do too.
  const uint64_t g = Rank1Generator(m);
  const Point2 s = HashShift(HashCombine(h, kSaltPrepassLattice));
  for (uint64_t j = 0; j < m; ++j) {
    out[j] = {Wrap(static_cast<double>(j) / m + s.x), Wrap(static_cast<double>((j * g) % m) / m + s.y)};
  }
}

StatusOr<PixelPlan> AlignedSampler::Plan(uint32_t x, uint32_t y, std::span<const std::span<const double>> block,
                                         Scratch& scratch) const {
  const int side = block_side();
  const size_t cells = static_cast<size_t>(side) * side, centre = cells / 2;
  if (block.size() != cells) {
    return Status::InvalidArgument("a block of " + std::to_string(block.size()) + " pixels; this sampler reads " +
                                   std::to_string(side) + " x " + std::to_string(side));
  }
  for (size_t k = 0; k < cells; ++k) {
    if (!block[k].empty() && block[k].size() != prepass_) {
      return Status::InvalidArgument("pixel " + std::to_string(k) + " of the block has " +
                                     std::to_string(block[k].size()) + " pre-pass values, not " +
                                     std::to_string(prepass_));
    }
  }
  if (block[centre].empty()) return Status::InvalidArgument("the block's centre (the pixel itself) has no values");
  Scratch::Impl& w = *scratch.impl_;
  if (w.patches.size() != cells) w.patches.resize(cells);
  const bool shared = options_.domain == PixelDomain::kShared;
  if (shared && w.crossings.size() != cells) w.crossings.resize(cells);
  static const EdgeLineOptions lines = LineOptions(), stacked_lines = StackedOptions();

  // Each pixel of the block: its pre-pass points again (a function of its
  // seed) beside the values the renderer measured there.
  for (size_t k = 0; k < cells; ++k) {
    SampledPatch& patch = w.patches[k];
    if (block[k].empty()) {
      patch.points.clear();
      patch.values.clear();
      continue;
    }
    const int64_t nx = static_cast<int64_t>(x) + static_cast<int64_t>(k % side) - radius_;
    const int64_t ny = static_cast<int64_t>(y) + static_cast<int64_t>(k / side) - radius_;
    patch.points.resize(prepass_);
    PrepassPoints(static_cast<uint32_t>(nx), static_cast<uint32_t>(ny), patch.points);
    patch.values.assign(block[k].begin(), block[k].end());
  }

  Found own, pooled;
  bool pooled_ok = false;
  if (!shared) {
    auto e = EstimateEdgeLines(w.patches[centre], lines);
    if (e.ok()) {
      own = FromEstimate(*e);
    } else {
      ++w.stats.fit_refused;
    }
    std::array<const SampledPatch*, 9> nine{};
    for (size_t k = 0; k < 9; ++k) nine[k] = w.patches[k].values.empty() ? nullptr : &w.patches[k];
    auto p = EstimateEdgeLinesPooled(nine, kPooledMargin, lines);
    if (p.ok()) {
      pooled = FromEstimate(*p);
      pooled_ok = true;
    } else {
      ++w.stats.fit_refused;
    }
  } else {
    w.stacked.assign(cells, nullptr);
    for (size_t k = 0; k < cells; ++k) {
      if (w.patches[k].values.empty()) continue;
      auto c = FindCrossings(w.patches[k], lines);
      if (!c.ok()) {
        if (k == centre) ++w.stats.fit_refused;
        continue;
      }
      w.crossings[k] = std::move(*c);
      w.stacked[k] = &w.crossings[k];
    }
    if (w.stacked[centre] != nullptr) {
      auto e = EstimateEdgeLines(*w.stacked[centre], lines);
      if (e.ok()) own = FromEstimate(*e);
    }
    auto p = EstimateEdgeLinesStacked(w.stacked, stacked_lines);
    if (p.ok()) {
      pooled = FromEstimate(*p);
      pooled_ok = true;
    } else {
      ++w.stats.fit_refused;
    }
  }
  // On footprints an unchecked pooled line made edges worse where the two
  // disagree; stacked, the pooled fit wins (docs/rendering.md).
  Found d = own;
  if (pooled_ok && pooled.directions > 0 &&
      (shared || own.directions == 0 || AxialDistanceDeg(pooled.theta1, own.theta1) <= kAgreeDeg)) {
    d = pooled;
  }

  PixelPlan plan;
  plan.x = x;
  plan.y = y;
  plan.directions = d.directions;
  plan.theta1_deg = d.theta1;
  plan.theta2_deg = d.theta2;
  AlignedPolicy policy;
  policy.two_directions = options_.two_directions;
  plan.choice = ChooseSet({d.directions, d.theta1, d.theta2}, policy);
  ++w.stats.pixels;
  if (plan.choice.kind == SetChoice::Kind::kFallback) {
    const bool continued = options_.reuse == PrepassReuse::kContinue && !lattice_prepass_;
    plan.main = continued ? PixelPlan::Main::kContinued : PixelPlan::Main::kOwenSobol;
    plan.main_seed = continued ? HashCombine(options_.seed, static_cast<uint64_t>(y) * options_.image_width + x)
                               : PixelHash(options_.seed, x, y, kSaltSet);
    return plan;
  }
  ++w.stats.with_direction;
  auto set = table_->Find(options_.n, options_.construction, plan.choice);
  if (!set.ok() && plan.choice.kind == SetChoice::Kind::kTwo && set.status().code() == Status::Code::kNotFound) {
    // A table without this pair: the stronger edge's set (documented).
    AlignedPolicy one = policy;
    one.two_directions = false;
    plan.choice = ChooseSet({d.directions, d.theta1, d.theta2}, one);
    plan.pair_fell_back = true;
    ++w.stats.pair_fell_back;
    set = table_->Find(options_.n, options_.construction, plan.choice);
  }
  if (!set.ok()) return set.status();
  if (plan.choice.kind == SetChoice::Kind::kTwo) ++w.stats.two_directions;
  plan.set = *set;
  plan.main = PixelPlan::Main::kSet;
  plan.shift = PixelShift(HashCombine(options_.seed, kSaltShift), x, y);
  return plan;
}

void AlignedSampler::MainPoints(const PixelPlan& plan, std::span<Point2> out) const {
  const std::span<Point2> points = out.first(std::min<size_t>(out.size(), options_.n));
  switch (plan.main) {
    case PixelPlan::Main::kOwenSobol:
      OwenScrambledSobolInto(plan.main_seed, 0, points);
      return;
    case PixelPlan::Main::kContinued:
      OwenScrambledSobolInto(plan.main_seed, prepass_, points);
      return;
    case PixelPlan::Main::kSet:
      break;
  }
  const TableSet& set = plan.set;
  if (set.lattice_generator != 0) {
    // The lattice's realization 0 under the pixel's shift (the points
    // alignset render's lattices take), folded after the shift for a
    // tent-lattice.
    Rank1LatticePointsInto(set.n, set.lattice_generator, 0, points);
    const double below_one = std::nextafter(1.0, 0.0);
    for (Point2& p : points) {
      p = ShiftPoint(p, plan.shift);
      if (set.folded) p = {std::min(TentFold(p.x), below_one), std::min(TentFold(p.y), below_one)};
    }
    return;
  }
  for (size_t i = 0; i < points.size(); ++i) points[i] = ShiftPoint((*set.points)[i], plan.shift);
}

double AlignedSampler::Estimate(const PixelPlan& plan, std::span<const double> prepass_values,
                                std::span<const double> main_values) const {
  const double pre = Mean(prepass_values), main = Mean(main_values);
  if (options_.reuse == PrepassReuse::kUnbiased || plan.main == PixelPlan::Main::kSet) {
    return weight_ * pre + (1.0 - weight_) * main;
  }
  if (plan.main == PixelPlan::Main::kOwenSobol) return main;  // after a lattice pre-pass: no sequence to continue
  // The pre-pass's sequence continued to T = M + N points: each aligned
  // power-of-two block (a net) weighted by its size cubed, the n^-3 of a
  // smooth pixel; the pre-pass lies in the first block (its values enter by
  // their sum).
  const uint32_t m = static_cast<uint32_t>(prepass_values.size()), total = m + static_cast<uint32_t>(main_values.size());
  uint32_t first_block = 0;
  for (uint32_t bit = 1u << 31; bit != 0; bit >>= 1) {
    if (total & bit) {
      first_block = bit;
      break;
    }
  }
  const bool one_mean = m > first_block;  // the pre-pass spans blocks: a plain mean of every point
  double estimate = 0.0, weights = 0.0;
  uint32_t begin = 0;
  for (uint32_t bit = 1u << 31; bit != 0; bit >>= 1) {
    const uint32_t size = one_mean ? (begin == 0 ? total : 0) : (total & bit);
    if (size == 0) continue;
    double sum = begin == 0 ? pre * m : 0.0;
    for (uint32_t k = std::max(begin, m); k < begin + size; ++k) sum += main_values[k - m];
    const double wt = std::pow(static_cast<double>(size), 3.0);
    estimate += wt * sum / size;
    weights += wt;
    begin += size;
    if (one_mean) break;
  }
  return estimate / weights;
}

}  // namespace alignset

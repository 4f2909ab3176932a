#include <alignset/prepass_fit.h>

#include <algorithm>
#include <array>
#include <bit>
#include <vector>

#include "core/analysis/edge_line_fit.h"
#include "core/sampling/owen_sobol.h"
#include "core/sampling/rank1_lattice.h"
#include "core/util/directions.h"
#include "core/util/hash.h"

namespace alignset {
namespace {

// The salt of the pre-pass lattice's shift: alignset render's, so the
// library and the renderer draw the same points; no sampler's salt, so the
// pre-pass is independent of every sampler's own randomization.
constexpr uint64_t kSaltPrepassLattice = 0x6c61747469636501ull;

// The edge-line fit's settings of record (docs/rendering.md, "Every sample
// counted"): a second line needs 15% of the crossings (a corner's shorter
// edge, pooled or stacked, still holds many); the stacked fit draws 24
// candidate lines (a block of 9 or 25 pixels supports each amply); a pooled
// footprint reads the samples within half a pixel; where the pixel's own fit
// and the pooled one disagree by more than 8 degrees on footprints, the
// pixel's own stands.
constexpr double kSecondLineShare = 0.15;
constexpr int kStackedCandidates = 24;
constexpr double kPooledMargin = 0.5;
constexpr double kAgreeDeg = 8.0;
// Crossings kept per Scratch: more than the largest block (9 x 9) twice over,
// so that a walk one pixel on finds most of its block again.
constexpr size_t kCachedCrossings = 192;
constexpr size_t kPairsPerSample = 4;

Point2 HashShift(uint64_t h) {
  return {static_cast<double>(h >> 11) * 0x1.0p-53, static_cast<double>(Mix64(h) >> 11) * 0x1.0p-53};
}

double Wrap(double u) { return u >= 1.0 ? u - 1.0 : u; }

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

// The estimate as directions, under the confidence floor (on the first
// line only: a second line's share is small by nature).
FittedDirections FromEstimate(const DirectionEstimate& e, int min_confidence_pct) {
  FittedDirections f;
  if (e.first.status != DirectionStatus::kFound || e.first.confidence * 100.0 < min_confidence_pct) return f;
  f.directions = 1;
  f.theta1_deg = e.first.theta_deg;
  f.confidence = e.first.confidence;
  if (e.has_second && e.second.status == DirectionStatus::kFound) {
    f.directions = 2;
    f.theta2_deg = e.second.theta_deg;
  }
  return f;
}

}  // namespace

struct PrepassFit::Scratch::Impl {
  EdgeLineScratch lines;              // the core fit's working memory
  DirectionEstimate own, pooled;      // its results, rewritten in place
  std::vector<SampledPatch> patches;  // the block's pre-passes
  std::vector<const PatchCrossings*> stacked;
  // Recently found crossings, by the pixel's pre-pass seed, count and a hash
  // of its values: the same pre-pass gives the same crossings, bit for bit.
  struct Cached {
    uint64_t seed = 0, values = 0;
    uint32_t count = 0;
    bool ok = false;
    uint64_t fit = 0;  // the last Fit that read it: never replaced during that Fit
    PatchCrossings crossings;
  };
  std::vector<Cached> cache;
  size_t next = 0;
  uint64_t fits = 0;
  uint32_t reserved_for = 0;  // the M the buffers were grown for
};

PrepassFit::Scratch::Scratch() : impl_(std::make_unique<Impl>()) {}
PrepassFit::Scratch::~Scratch() = default;
PrepassFit::Scratch::Scratch(Scratch&&) noexcept = default;
PrepassFit::Scratch& PrepassFit::Scratch::operator=(Scratch&&) noexcept = default;

StatusOr<PrepassFit> PrepassFit::Create(const PrepassFitOptions& options) {
  if (options.image_width == 0) return Status::InvalidArgument("image_width must be at least 1");
  if (options.prepass_samples < 16 || options.prepass_samples > 4096) {
    return Status::InvalidArgument("prepass_samples must be in [16, 4096], got " +
                                   std::to_string(options.prepass_samples));
  }
  if (options.stack_radius < 1 || options.stack_radius > 4) {
    return Status::InvalidArgument("stack_radius must be in [1, 4], got " + std::to_string(options.stack_radius));
  }
  if (options.min_confidence_pct < 0 || options.min_confidence_pct > 100) {
    return Status::InvalidArgument("min_confidence_pct must be in [0, 100]");
  }
  PrepassFit f;
  f.options_ = options;
  return f;
}

uint64_t PrepassFit::PrepassSeed(uint32_t x, uint32_t y) const {
  return HashCombine(options_.seed, static_cast<uint64_t>(y) * options_.image_width + x);
}

void PrepassFit::PrepassPoints(uint32_t x, uint32_t y, std::span<Point2> out) const {
  const uint64_t h = PrepassSeed(x, y);
  const uint32_t m = static_cast<uint32_t>(std::min<size_t>(out.size(), options_.prepass_samples));
  if (options_.lattice_points) {
    PrepassLatticePointsInto(h, out.first(m));
  } else {
    OwenScrambledSobolInto(h, 0, out.first(m));
  }
}

void PrepassLatticePointsInto(uint64_t pixel_seed, std::span<Point2> out) {
  const uint64_t m = out.size();
  if (m == 0) return;
  const uint64_t g = Rank1Generator(static_cast<uint32_t>(m));
  const Point2 s = HashShift(HashCombine(pixel_seed, kSaltPrepassLattice));
  for (uint64_t j = 0; j < m; ++j) {
    out[j] = {Wrap(static_cast<double>(j) / m + s.x), Wrap(static_cast<double>((j * g) % m) / m + s.y)};
  }
}

StatusOr<FittedDirections> PrepassFit::Fit(uint32_t x, uint32_t y, std::span<const std::span<const double>> block,
                                           Scratch& scratch) const {
  const int side = block_side(), radius = block_radius();
  const size_t cells = static_cast<size_t>(side) * side, centre = cells / 2;
  const uint32_t m = options_.prepass_samples;
  if (block.size() != cells) {
    return Status::InvalidArgument("a block of " + std::to_string(block.size()) + " pixels; this fit reads " +
                                   std::to_string(side) + " x " + std::to_string(side));
  }
  for (size_t k = 0; k < cells; ++k) {
    if (!block[k].empty() && block[k].size() != m) {
      return Status::InvalidArgument("pixel " + std::to_string(k) + " of the block has " +
                                     std::to_string(block[k].size()) + " pre-pass values, not " + std::to_string(m));
    }
  }
  if (block[centre].empty()) return Status::InvalidArgument("the block's centre (the pixel itself) has no values");
  Scratch::Impl& w = *scratch.impl_;
  if (w.patches.size() != cells) w.patches.resize(cells);
  // The buffers grown once for the largest block of this M: a patch's
  // neighbouring pairs that jump, at most kPairsPerSample a sample (the pairs
  // within the fit's 1.6 spacings of a stratified set), so that no pixel
  // allocates afterwards.
  const size_t max_crossings = kPairsPerSample * m;
  if (w.reserved_for < m) {
    const size_t most = 81;  // a 9 x 9 block
    w.lines.Reserve(9 * m, most * max_crossings, most);
    for (SampledPatch& p : w.patches) {
      p.points.reserve(m);
      p.values.reserve(m);
    }
    w.patches.reserve(most);
    w.stacked.reserve(most);
    // A lobe's reason ("no straight edge: 12 of 140 crossings on one line")
    // is written into the string the estimate already holds.
    for (DirectionEstimate* e : {&w.own, &w.pooled}) {
      e->first.reason.reserve(96);
      e->second.reason.reserve(96);
    }
    w.reserved_for = m;
  }
  static const EdgeLineOptions lines = LineOptions(), stacked_lines = StackedOptions();
  const bool shared = options_.domain == PixelDomain::kShared;

  // Each pixel of the block: its pre-pass points again (a function of its
  // seed) beside the values the renderer measured there.
  auto fill = [&](size_t k) {
    SampledPatch& patch = w.patches[k];
    const int64_t nx = static_cast<int64_t>(x) + static_cast<int64_t>(k % side) - radius;
    const int64_t ny = static_cast<int64_t>(y) + static_cast<int64_t>(k / side) - radius;
    patch.points.resize(m);
    PrepassPoints(static_cast<uint32_t>(nx), static_cast<uint32_t>(ny), patch.points);
    patch.values.assign(block[k].begin(), block[k].end());
    return PrepassSeed(static_cast<uint32_t>(nx), static_cast<uint32_t>(ny));
  };

  FittedDirections own, pooled;
  bool pooled_ok = false;
  FittedDirections out;
  if (!shared) {
    for (size_t k = 0; k < cells; ++k) {
      if (block[k].empty()) {
        w.patches[k].points.clear();
        w.patches[k].values.clear();
      } else {
        fill(k);
      }
    }
    if (EstimateEdgeLines(w.patches[centre], lines, w.lines, &w.own).ok()) {
      own = FromEstimate(w.own, options_.min_confidence_pct);
    } else {
      out.own_refused = true;
    }
    std::array<const SampledPatch*, 9> nine{};
    for (size_t k = 0; k < 9; ++k) nine[k] = block[k].empty() ? nullptr : &w.patches[k];
    if (EstimateEdgeLinesPooled(nine, kPooledMargin, lines, w.lines, &w.pooled).ok()) {
      pooled = FromEstimate(w.pooled, options_.min_confidence_pct);
      pooled_ok = true;
    } else {
      out.pooled_refused = true;
    }
  } else {
    if (w.cache.size() != kCachedCrossings) w.cache.assign(kCachedCrossings, {});
    const uint64_t call = ++w.fits;
    w.stacked.assign(cells, nullptr);
    for (size_t k = 0; k < cells; ++k) {
      if (block[k].empty()) continue;
      const int64_t nx = static_cast<int64_t>(x) + static_cast<int64_t>(k % side) - radius;
      const int64_t ny = static_cast<int64_t>(y) + static_cast<int64_t>(k / side) - radius;
      const uint64_t seed = PrepassSeed(static_cast<uint32_t>(nx), static_cast<uint32_t>(ny));
      uint64_t values = HashCombine(options_.lattice_points ? 1 : 2, m);
      for (double v : block[k]) values = HashCombine(values, std::bit_cast<uint64_t>(v));
      Scratch::Impl::Cached* hit = nullptr;
      for (auto& c : w.cache) {
        if (c.count == m && c.seed == seed && c.values == values) hit = &c;
      }
      if (hit == nullptr) {
        fill(k);
        // The oldest entry this Fit has not read (the cache holds more than
        // a block, so there is one).
        while (w.cache[w.next].fit == call) w.next = (w.next + 1) % w.cache.size();
        hit = &w.cache[w.next];
        w.next = (w.next + 1) % w.cache.size();
        hit->seed = seed;
        hit->values = values;
        hit->count = m;
        hit->crossings.midpoints.reserve(max_crossings);
        hit->ok = FindCrossings(w.patches[k], lines, w.lines, &hit->crossings).ok();
      }
      hit->fit = call;
      if (hit->ok) {
        w.stacked[k] = &hit->crossings;
      } else if (k == centre) {
        out.own_refused = true;
      }
    }
    if (w.stacked[centre] != nullptr) {
      if (EstimateEdgeLines(*w.stacked[centre], lines, w.lines, &w.own).ok()) {
        own = FromEstimate(w.own, options_.min_confidence_pct);
      } else {
        out.own_refused = true;
      }
    }
    if (EstimateEdgeLinesStacked(w.stacked, stacked_lines, w.lines, &w.pooled).ok()) {
      pooled = FromEstimate(w.pooled, options_.min_confidence_pct);
      pooled_ok = true;
    } else {
      out.pooled_refused = true;
    }
  }
  // On footprints an unchecked pooled line made edges worse where the two
  // disagree; stacked, the pooled fit wins (docs/rendering.md).
  FittedDirections d = own;
  if (pooled_ok && pooled.directions > 0 &&
      (shared || own.directions == 0 || AxialDistanceDeg(pooled.theta1_deg, own.theta1_deg) <= kAgreeDeg)) {
    d = pooled;
  }
  d.own_refused = out.own_refused;
  d.pooled_refused = out.pooled_refused;
  return d;
}

}  // namespace alignset

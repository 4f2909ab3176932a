#include "render/pixel_samplers.h"

#include <algorithm>
#include <cmath>

#include <alignset/aligned_sampler.h>
#include <alignset/pixel_shift.h>
#include <alignset/set_choice.h>

#include "core/sampling/owen_sobol.h"
#include "core/sampling/rank1_lattice.h"
#include "core/sampling/samplers.h"
#include "core/sampling/shear.h"
#include "core/util/angles.h"
#include "core/util/hash.h"
#include "render/prepass_reuse.h"

namespace alignset::render {

uint64_t PixelHash(uint64_t seed, int x, int y, uint64_t salt) {
  return HashCombine(HashCombine(HashCombine(seed, salt), static_cast<uint64_t>(x)),
                     static_cast<uint64_t>(y));
}

Point2 HashShift(uint64_t h) {
  return {static_cast<double>(h >> 11) * 0x1.0p-53,
          static_cast<double>(Mix64(h) >> 11) * 0x1.0p-53};
}

namespace {

double Mean(const PixelIntegrand& f, const PointSet& points) {
  double sum = 0.0;
  for (const Point2& p : points) sum += f.Eval({p.x, p.y});
  return sum / static_cast<double>(points.size());
}

double MeanShifted(const PixelIntegrand& f, const PointSet& points, Point2 s) {
  double sum = 0.0;
  for (const Point2& p : points) {
    double x = p.x + s.x, y = p.y + s.y;
    if (x >= 1.0) x -= 1.0;
    if (y >= 1.0) y -= 1.0;
    sum += f.Eval({x, y});
  }
  return sum / static_cast<double>(points.size());
}

// Salts keep the randomizations of different samplers independent.
enum Salt : uint64_t { kSaltSet = 1, kSaltShift = 2, kSaltPool = 3, kSaltLine = 4, kSaltAngle = 5 };

class PerPixelRegistry : public PixelSampler {
 public:
  PerPixelRegistry(std::string name, uint32_t n, bool shift)
      : name_(std::move(name)), n_(n), shift_(shift) {}
  double Estimate(const PixelIntegrand& f, const PixelTask& t) const override {
    const uint64_t h = PixelHash(t.seed, t.x, t.y, kSaltSet);
    if (name_ == "owen-sobol") return Mean(f, OwenScrambledSobol(n_, h));
    auto set = Sample(name_, n_, h);
    if (!set.ok()) return std::nan("");
    return shift_ ? MeanShifted(f, *set, HashShift(PixelHash(t.seed, t.x, t.y, kSaltShift)))
                  : Mean(f, *set);
  }

 private:
  std::string name_;
  uint32_t n_;
  bool shift_;
};

// A pool of sets plus a Cranley-Patterson shift per pixel.
class PooledShifted : public PixelSampler {
 public:
  PooledShifted(std::vector<PointSet> pool, const std::vector<PixelDirection>* shear_by)
      : pool_(std::move(pool)), shear_by_(shear_by) {}
  double Estimate(const PixelIntegrand& f, const PixelTask& t) const override {
    const PointSet& base = pool_[PixelHash(t.seed, t.x, t.y, kSaltPool) % pool_.size()];
    const Point2 s = HashShift(PixelHash(t.seed, t.x, t.y, kSaltShift));
    if (shear_by_) {
      const PixelDirection& d = (*shear_by_)[t.index];
      if (d.kind != PixelDirection::Kind::kNone) return MeanShifted(f, Shear(base, d.theta1), s);
    }
    return MeanShifted(f, base, s);
  }

 private:
  std::vector<PointSet> pool_;
  const std::vector<PixelDirection>* shear_by_;
};

class Rank1Shifted : public PixelSampler {
 public:
  explicit Rank1Shifted(uint32_t n) {
    const uint32_t g = Rank1Generator(n);
    for (uint32_t k = 0; k < n; ++k) {
      base_.push_back({static_cast<double>(k) / n,
                       static_cast<double>((static_cast<uint64_t>(k) * g) % n) / n});
    }
  }
  double Estimate(const PixelIntegrand& f, const PixelTask& t) const override {
    return MeanShifted(f, base_, HashShift(PixelHash(t.seed, t.x, t.y, kSaltShift)));
  }

 private:
  PointSet base_;
};

class ScreenSpace : public PixelSampler {
 public:
  ScreenSpace(uint32_t n, const ShiftTile& tile) : sampler_(n, tile) {}
  double Estimate(const PixelIntegrand& f, const PixelTask& t) const override {
    // One shift shared by the whole screen randomizes a render and keeps the
    // tile's relative shifts, hence its blue-noise error.
    return Mean(f, sampler_.PixelSet(t.x, t.y, HashShift(HashCombine(t.seed, kSaltShift))));
  }

 private:
  ScreenSpaceRank1 sampler_;
};

class Aligned : public PixelSampler {
 public:
  Aligned(uint32_t n, const RenderSets& sets, const std::vector<PixelDirection>* dirs, AlignedPolicy policy,
          bool per_pixel_shift)
      : n_(n), table_(sets.table), construction_(sets.construction), dirs_(dirs), policy_(policy),
        shift_(per_pixel_shift) {
    if (table_) sections_ = table_->Resolve(sets.n, construction_);
  }
  Aligned(const Aligned&) = delete;  // sections_ names construction_
  Aligned& operator=(const Aligned&) = delete;
  double Estimate(const PixelIntegrand& f, const PixelTask& t) const override {
    // The sampler library's points (<alignset/aligned_sampler.h>): the
    // pixel's own Owen-Sobol points without a direction, else the served
    // set under the pixel's shift.
    const SetChoice c = ChooseSet(RecipeDirections((*dirs_)[t.index]), policy_);
    thread_local std::vector<Point2> points;
    if (c.kind == SetChoice::Kind::kFallback) {
      points.resize(n_);
      FallbackPixelPoints(t.seed, static_cast<uint32_t>(t.x), static_cast<uint32_t>(t.y), points);
      return Mean(f, points);
    }
    if (!table_) return std::nan("");
    auto found = table_->Find(sections_, c);
    if (!found.ok()) return std::nan("");  // a set the table was not filled with: shows up, never hides
    const TableSet& set = *found;
    const Point2 s = PixelShift(HashCombine(t.seed, kSaltShift), shift_ ? t.x : 0, shift_ ? t.y : 0);
    points.resize(set.n);
    SetPixelPoints(set, s, points);
    return Mean(f, points);
  }

 private:
  uint32_t n_;
  std::shared_ptr<const SetTable> table_;
  std::string construction_;
  SetTable::Sections sections_;  // resolved once, for every pixel
  const std::vector<PixelDirection>* dirs_;
  AlignedPolicy policy_;
  bool shift_;
};

// The direction (degrees) a line or segment takes in a pixel.
double LineDirection(LineOrientation o, const std::vector<PixelDirection>* dirs,
                     const PixelTask& t) {
  const double random = 180.0 * HashShift(PixelHash(t.seed, t.x, t.y, kSaltAngle)).x;
  if (o == LineOrientation::kRandom || !dirs) return random;
  const PixelDirection& d = (*dirs)[t.index];
  if (d.kind == PixelDirection::Kind::kNone) return random;
  return o == LineOrientation::kNormal ? d.theta1 : d.theta1 + 90.0;
}

class Lines : public PixelSampler {
 public:
  Lines(uint32_t n, LineOrientation o, const std::vector<PixelDirection>* dirs)
      : n_(n), o_(o), dirs_(dirs) {}
  double Estimate(const PixelIntegrand& f, const PixelTask& t) const override {
    return LineEstimate(f, n_, LineDirection(o_, dirs_, t), PixelHash(t.seed, t.x, t.y, kSaltLine));
  }

 private:
  uint32_t n_;
  LineOrientation o_;
  const std::vector<PixelDirection>* dirs_;
};

class Segments : public PixelSampler {
 public:
  Segments(uint32_t n, LineOrientation o, const std::vector<PixelDirection>* dirs, double length)
      : n_(n), o_(o), dirs_(dirs), length_(length) {}
  double Estimate(const PixelIntegrand& f, const PixelTask& t) const override {
    return SegmentEstimate(f, n_, LineDirection(o_, dirs_, t), length_,
                           PixelHash(t.seed, t.x, t.y, kSaltLine));
  }

 private:
  uint32_t n_;
  LineOrientation o_;
  const std::vector<PixelDirection>* dirs_;
  double length_;
};

bool Pooled(const std::string& name) {
  return name == "pmj02" || name == "pmj02bn" || name == "poisson-dart" ||
         name == "poisson-bridson";
}
bool Deterministic(const std::string& name) {
  return name == "grid" || name == "halton" || name == "hammersley" || name == "sobol";
}
// Randomized, but not uniformly: scrambled Hammersley keeps x = i / N, a
// left-endpoint rule in x (biased; tests/render caught it). A CP shift makes
// every such set an unbiased estimator.
bool NeedsShift(const std::string& name) { return name == "hammersley-scrambled"; }

StatusOr<std::vector<PointSet>> MakePool(const std::string& name, uint32_t n, int count) {
  std::vector<PointSet> pool;
  for (int k = 0; k < count; ++k) {
    auto set = Sample(name, n, HashCombine(0x9001ULL, static_cast<uint64_t>(k)));
    if (!set.ok()) return set.status();
    pool.push_back(std::move(*set));
  }
  return pool;
}

}  // namespace

double LineEstimate(const PixelIntegrand& f, uint32_t n, double line_deg, uint64_t h) {
  const double a = DegToRad(line_deg);
  const V2 d = {std::cos(a), std::sin(a)}, nrm = {-d.y, d.x};
  double t_min = 1e300, t_max = -1e300;
  for (V2 c : {V2{0, 0}, V2{1, 0}, V2{0, 1}, V2{1, 1}}) {
    t_min = std::min(t_min, Dot(nrm, c));
    t_max = std::max(t_max, Dot(nrm, c));
  }
  const double width = t_max - t_min;
  Pcg32 rng(h);
  double sum = 0.0;
  for (uint32_t i = 0; i < n; ++i) {
    const double t = t_min + width * (i + rng.NextDouble()) / n;
    double lo = -1e300, hi = 1e300;
    bool empty = false;
    for (int axis = 0; axis < 2; ++axis) {
      const double da = axis ? d.y : d.x, pa = t * (axis ? nrm.y : nrm.x);
      if (std::abs(da) < 1e-15) {
        if (pa < 0.0 || pa > 1.0) empty = true;
        continue;
      }
      const double s1 = (0.0 - pa) / da, s2 = (1.0 - pa) / da;
      lo = std::max(lo, std::min(s1, s2));
      hi = std::min(hi, std::max(s1, s2));
    }
    if (empty || hi <= lo) continue;
    auto clamp01 = [](V2 p) { return V2{std::clamp(p.x, 0.0, 1.0), std::clamp(p.y, 0.0, 1.0)}; };
    sum += f.LineIntegral(clamp01(t * nrm + lo * d), clamp01(t * nrm + hi * d));
  }
  return sum * width / n;
}

double SegmentEstimate(const PixelIntegrand& f, uint32_t n, double segment_deg, double length,
                       uint64_t h) {
  const double a = DegToRad(segment_deg);
  const V2 d = {std::cos(a), std::sin(a)};
  const PointSet centres = OwenScrambledSobol(n, h);
  double sum = 0.0;
  std::vector<double> cuts;
  for (const Point2& c0 : centres) {
    const V2 c = {c0.x, c0.y};
    const double s0 = -0.5 * length, s1 = 0.5 * length;
    cuts.assign({s0, s1});
    // Where the segment crosses the lines x = k and y = k of the periodic
    // repetition: between two cuts it lies in one copy of the pixel.
    for (int axis = 0; axis < 2; ++axis) {
      const double da = axis ? d.y : d.x, ca = axis ? c.y : c.x;
      if (std::abs(da) < 1e-15) continue;
      const double e0 = ca + s0 * da, e1 = ca + s1 * da;
      for (double k = std::ceil(std::min(e0, e1)); k <= std::floor(std::max(e0, e1)); k += 1.0) {
        const double s = (k - ca) / da;
        if (s > s0 && s < s1) cuts.push_back(s);
      }
    }
    std::sort(cuts.begin(), cuts.end());
    for (size_t i = 0; i + 1 < cuts.size(); ++i) {
      if (cuts[i + 1] <= cuts[i]) continue;
      const V2 mid = c + (0.5 * (cuts[i] + cuts[i + 1])) * d;
      const V2 cell = {std::floor(mid.x), std::floor(mid.y)};
      auto local = [&](double s) {
        const V2 p = c + s * d - cell;
        return V2{std::clamp(p.x, 0.0, 1.0), std::clamp(p.y, 0.0, 1.0)};
      };
      sum += f.LineIntegral(local(cuts[i]), local(cuts[i + 1]));
    }
  }
  return sum / (length * n);
}

std::vector<std::string> RenderSamplerNames() {
  return {"pmj02bn-sheared", "pmj02bn-sheared-exact", "screen-space-rank1", "aligned",
          "aligned-exact", "aligned-lattice", "aligned-lattice-exact", "aligned-tent-lattice",
          "aligned-tent-lattice-exact", "line", "segment"};
}

namespace {

StatusOr<std::unique_ptr<PixelSampler>> MakeBaseSampler(const SamplerConfig& c) {
  const std::string& name = c.name;
  if (c.n < 1) return Status::InvalidArgument(name + ": N must be at least 1");
  auto need_dirs = [&](const std::vector<PixelDirection>* d) -> Status {
    return d ? Status::Ok()
             : Status::InvalidArgument(name + " needs a direction map (internal: none given)");
  };
  if (name == "pmj02bn-sheared" || name == "pmj02bn-sheared-exact") {
    const auto* dirs = name == "pmj02bn-sheared" ? c.estimated : c.exact;
    if (Status s = need_dirs(dirs); !s.ok()) return s;
    auto pool = MakePool("pmj02bn", c.n, c.pool);
    if (!pool.ok()) return pool.status();
    return std::unique_ptr<PixelSampler>(new PooledShifted(std::move(*pool), dirs));
  }
  if (name == "screen-space-rank1") {
    if (!c.tile) return Status::InvalidArgument(name + " needs a shift tile (internal: none given)");
    return std::unique_ptr<PixelSampler>(new ScreenSpace(c.n, *c.tile));
  }
  if (name == "aligned" || name == "aligned-exact" || name == "aligned-lattice" ||
      name == "aligned-lattice-exact" || name == "aligned-tent-lattice" || name == "aligned-tent-lattice-exact") {
    const bool exact = name == "aligned-exact" || name == "aligned-lattice-exact" ||
                       name == "aligned-tent-lattice-exact";
    const bool tent = name.find("tent") != std::string::npos;
    const auto* dirs = exact ? c.exact : c.estimated;
    if (Status s = need_dirs(dirs); !s.ok()) return s;
    const char* construction = tent ? "tent-lattice" : name.find("lattice") != std::string::npos ? "lattice" : "optimized";
    if (!c.sets || c.sets->n != c.n || c.sets->construction != construction) {
      return Status::InvalidArgument(name + " needs the " +
                                     (tent ? "tent-folded lattice"
                                           : name.find("lattice") != std::string::npos ? "lattice" : "aligned") +
                                     " sets of N = " + std::to_string(c.n));
    }
    return std::unique_ptr<PixelSampler>(
        new Aligned(c.n, *c.sets, dirs, c.policy, c.per_pixel_shift));
  }
  if (name == "line" || name == "segment") {
    if (c.orientation != LineOrientation::kRandom) {
      if (Status s = need_dirs(c.estimated); !s.ok()) return s;
    }
    if (name == "line") return std::unique_ptr<PixelSampler>(new Lines(c.n, c.orientation, c.estimated));
    if (!(c.segment_length > 0.0 && c.segment_length <= 1.0)) {
      return Status::InvalidArgument("segment: length must be in (0, 1] pixel widths");
    }
    return std::unique_ptr<PixelSampler>(
        new Segments(c.n, c.orientation, c.estimated, c.segment_length));
  }
  if (name == "rank1-lattice") return std::unique_ptr<PixelSampler>(new Rank1Shifted(c.n));
  // The registry: check the name and N once, up front, for a clear error.
  auto probe = Sample(name, c.n, 1);
  if (!probe.ok()) return probe.status();
  if (Pooled(name)) {
    auto pool = MakePool(name, c.n, c.pool);
    if (!pool.ok()) return pool.status();
    return std::unique_ptr<PixelSampler>(new PooledShifted(std::move(*pool), nullptr));
  }
  if (Deterministic(name)) {
    return std::unique_ptr<PixelSampler>(new PooledShifted({std::move(*probe)}, nullptr));
  }
  return std::unique_ptr<PixelSampler>(new PerPixelRegistry(name, c.n, NeedsShift(name)));
}

}  // namespace

bool ReadsEstimatedDirections(const SamplerConfig& c) {
  if (c.name == "line" || c.name == "segment") return c.orientation != LineOrientation::kRandom;
  return c.name == "aligned" || c.name == "aligned-lattice" || c.name == "aligned-tent-lattice" ||
         c.name == "pmj02bn-sheared";
}

StatusOr<std::unique_ptr<PixelSampler>> MakePixelSampler(const SamplerConfig& c) {
  auto base = MakeBaseSampler(c);
  if (!base.ok() || !c.reuse_prepass || !ReadsEstimatedDirections(c)) return base;
  const bool owen_sobol_when_none =
      (c.name == "aligned" || c.name == "aligned-lattice" || c.name == "aligned-tent-lattice") &&
                                    c.policy.none == AlignedPolicy::None::kOwenSobol;
  return ReusePrepass(std::move(*base), c.estimated, c.n, c.continue_prepass && owen_sobol_when_none);
}

}  // namespace alignset::render

#include "core/analysis/edge_line_fit.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "core/util/directions.h"
#include "core/util/hash.h"

namespace alignset {
namespace {

struct Line {
  double cx = 0.0, cy = 0.0;  // a point on it
  double nx = 0.0, ny = 0.0;  // unit normal
};

double Distance(const Line& l, const Point2& p) {
  return std::fabs((p.x - l.cx) * l.nx + (p.y - l.cy) * l.ny);
}

void Inliers(const Line& l, const std::vector<Point2>& m, const std::vector<size_t>& among, double band,
             std::vector<size_t>* in) {
  in->clear();
  for (size_t i : among) {
    if (Distance(l, m[i]) <= band) in->push_back(i);
  }
}

// Total least squares: through the centroid, normal along the covariance's
// smaller eigenvector.
Line FitLine(const std::vector<Point2>& m, const std::vector<size_t>& idx) {
  Line l;
  for (size_t i : idx) l.cx += m[i].x, l.cy += m[i].y;
  l.cx /= idx.size(), l.cy /= idx.size();
  double sxx = 0.0, syy = 0.0, sxy = 0.0;
  for (size_t i : idx) {
    const double dx = m[i].x - l.cx, dy = m[i].y - l.cy;
    sxx += dx * dx, syy += dy * dy, sxy += dx * dy;
  }
  // The major axis is at angle phi = atan2(2 sxy, sxx - syy) / 2; the
  // normal is perpendicular to it.
  const double phi = 0.5 * std::atan2(2.0 * sxy, sxx - syy);
  l.nx = -std::sin(phi), l.ny = std::cos(phi);
  return l;
}

// Whether the line meets the options' focus box (always, without one): the
// box's corners do not all lie on one side of it.
bool Crosses(const Line& l, const EdgeLineOptions& o) {
  if (!o.focus) return true;
  double lo = 0.0, hi = 0.0;
  bool first = true;
  for (double x : {o.focus_x0, o.focus_x1}) {
    for (double y : {o.focus_y0, o.focus_y1}) {
      const double s = (x - l.cx) * l.nx + (y - l.cy) * l.ny;
      lo = first ? s : std::min(lo, s);
      hi = first ? s : std::max(hi, s);
      first = false;
    }
  }
  return lo <= 0.0 && hi >= 0.0;
}

bool InFocus(const Point2& p, const EdgeLineOptions& o) {
  return !o.focus || (p.x >= o.focus_x0 && p.x <= o.focus_x1 && p.y >= o.focus_y0 && p.y <= o.focus_y1);
}

struct Found {
  bool ok = false;
  Line line;
  std::vector<size_t> inliers;
  void Clear() {
    ok = false;
    line = Line{};
    inliers.clear();
  }
};

// The buffers every step below reuses (EdgeLineScratch::Impl holds one).
struct Work {
  std::vector<uint32_t> cell_start, cell_fill, cell_order;
  std::vector<int> cell_of;
  std::vector<size_t> all, rest, off, near, anchors, candidate;
  std::vector<char> flags;
  Found first, second, refit;
  std::vector<std::vector<size_t>> by_patch;
  std::vector<double> cx, cy, count;
};

// The best of the candidate lines through two crossings of `among`, refined.
void BestLine(const std::vector<Point2>& m, const std::vector<size_t>& among, double band, const EdgeLineOptions& o,
              uint64_t seed, Work& w, Found* best) {
  best->Clear();
  if (among.size() < 2) return;
  // With a focus box, a line must rest on the box's own evidence: one of its
  // two crossings lies in the box, and so do at least two of its inliers.
  std::vector<size_t>& anchors = w.anchors;
  anchors.clear();
  for (size_t i : among) {
    if (InFocus(m[i], o)) anchors.push_back(i);
  }
  if (anchors.size() < 2) return;
  // Long baselines first (a third of the patch: accurate candidates); an
  // edge that only clips a corner has none, and gets short ones.
  for (double baseline : {1.0 / 3.0, 4.0 * band}) {
    Pcg32 rng(seed);
    int tried = 0;
    for (int draw = 0; draw < 8 * o.candidates && tried < o.candidates; ++draw) {
      const size_t a = anchors[rng.NextU32() % anchors.size()], b = among[rng.NextU32() % among.size()];
      const double dx = m[b].x - m[a].x, dy = m[b].y - m[a].y, len = std::hypot(dx, dy);
      if (len < baseline) continue;
      const Line l{m[a].x, m[a].y, -dy / len, dx / len};
      if (!Crosses(l, o)) continue;
      ++tried;
      Inliers(l, m, among, band, &w.candidate);
      if (w.candidate.size() > best->inliers.size()) {
        best->ok = true;
        best->line = l;
        std::swap(best->inliers, w.candidate);
      }
    }
    if (best->ok) break;
  }
  if (!best->ok) return;
  for (int refine = 0; refine < 2 && best->inliers.size() >= 2; ++refine) {
    const Line l = FitLine(m, best->inliers);
    Inliers(l, m, among, band, &w.candidate);
    if (w.candidate.size() < 2 || !Crosses(l, o)) break;
    best->line = l;
    std::swap(best->inliers, w.candidate);
  }
  if (o.focus) {
    size_t inside = 0;
    for (size_t i : best->inliers) inside += InFocus(m[i], o);
    if (inside < 2) best->ok = false;
  }
}

double NormalDegrees(const Line& l) {
  return ReduceDirection(std::atan2(l.ny, l.nx) * 180.0 / M_PI);
}

// A lobe reset to its defaults, its reason string kept (cleared) so that the
// next reason is written into the memory it already holds.
void Reset(DirectionLobe* lobe) {
  std::string reason = std::move(lobe->reason);
  *lobe = DirectionLobe{};
  reason.clear();
  lobe->reason = std::move(reason);
}

void Reset(DirectionEstimate* out) {
  std::string first = std::move(out->first.reason), second = std::move(out->second.reason);
  *out = DirectionEstimate{};
  first.clear();
  second.clear();
  out->first.reason = std::move(first);
  out->second.reason = std::move(second);
}

void SetNone(const char* reason, DirectionLobe* lobe) {
  Reset(lobe);
  lobe->reason.assign(reason);
}

// Neither lobe found, for one reason.
void NoLines(const char* reason, DirectionEstimate* out) {
  SetNone(reason, &out->first);
  SetNone(reason, &out->second);
}

void SetLobe(const Found& f, size_t crossings, DirectionLobe* lobe) {
  Reset(lobe);
  lobe->status = DirectionStatus::kFound;
  lobe->theta_deg = lobe->fit_theta_deg = NormalDegrees(f.line);
  lobe->confidence = static_cast<double>(f.inliers.size()) / static_cast<double>(crossings);
}

// Crossings of several patches over one domain: crossing i belongs to patch
// of[i], one of `patches`; the centre patch is the pixel's own.
struct Stack {
  std::vector<Point2> m;
  std::vector<int> of;
  int patches = 0;
  int centre = 0;
};

// The parallel lines with normal (nx, ny), one per patch, each at the
// offset whose band of width 2 band holds most of that patch's crossings in
// by_patch (a patch without the edge adds what lies in its best band, a few
// strays at most): each patch's best band as [first, first + count) of its
// crossings sorted by offset (ties by index), in `sorted`.
struct ParallelBands {
  std::vector<std::pair<double, size_t>> sorted;  // every patch's crossings, patch after patch
  std::vector<size_t> begin, first, count;        // per patch
  size_t total = 0, centre = 0;                   // inliers in all, in the centre patch
};

void FindParallelBands(const Stack& s, const std::vector<std::vector<size_t>>& by_patch, double nx,
                       double ny, double band, ParallelBands* b) {
  b->sorted.clear();
  b->begin.assign(by_patch.size(), 0);
  b->first.assign(by_patch.size(), 0);
  b->count.assign(by_patch.size(), 0);
  b->total = b->centre = 0;
  for (size_t k = 0; k < by_patch.size(); ++k) {
    const std::vector<size_t>& crossings = by_patch[k];
    const size_t at = b->sorted.size();
    b->begin[k] = at;
    if (crossings.empty()) continue;
    for (size_t i : crossings) b->sorted.push_back({s.m[i].x * nx + s.m[i].y * ny, i});
    const auto p = b->sorted.begin() + static_cast<std::ptrdiff_t>(at);
    std::sort(p, b->sorted.end());
    const size_t n = crossings.size();
    size_t best_lo = 0, best_count = 0;
    for (size_t lo = 0, hi = 0; lo < n; ++lo) {
      while (hi < n && p[hi].first - p[lo].first <= 2.0 * band) ++hi;
      if (hi - lo > best_count) best_count = hi - lo, best_lo = lo;
    }
    b->first[k] = best_lo;
    b->count[k] = best_count;
    b->total += best_count;
    if (static_cast<int>(k) == s.centre) b->centre = best_count;
  }
}

// The inliers of FindParallelBands's lines, patch after patch.
void BandInliers(const ParallelBands& b, std::vector<size_t>* in) {
  in->clear();
  for (size_t k = 0; k < b.begin.size(); ++k) {
    for (size_t j = 0; j < b.count[k]; ++j) in->push_back(b.sorted[b.begin[k] + b.first[k] + j].second);
  }
}

// Total least squares on parallel lines: each patch's inliers about their
// own centroid, the scatter pooled.
Line FitParallel(const Stack& s, const std::vector<size_t>& idx, Work& w) {
  std::vector<double>&cx = w.cx, &cy = w.cy, &count = w.count;
  cx.assign(static_cast<size_t>(s.patches), 0.0);
  cy.assign(static_cast<size_t>(s.patches), 0.0);
  count.assign(static_cast<size_t>(s.patches), 0.0);
  for (size_t i : idx) cx[s.of[i]] += s.m[i].x, cy[s.of[i]] += s.m[i].y, count[s.of[i]] += 1.0;
  double sxx = 0.0, syy = 0.0, sxy = 0.0;
  for (size_t i : idx) {
    const int k = s.of[i];
    const double dx = s.m[i].x - cx[k] / count[k], dy = s.m[i].y - cy[k] / count[k];
    sxx += dx * dx, syy += dy * dy, sxy += dx * dy;
  }
  const double phi = 0.5 * std::atan2(2.0 * sxy, sxx - syy);
  Line l;
  l.nx = -std::sin(phi), l.ny = std::cos(phi);
  return l;
}

// The crossings of `among`, patch by patch (the lists keep their memory).
const std::vector<std::vector<size_t>>& ByPatch(const Stack& s, const std::vector<size_t>& among, Work& w) {
  if (w.by_patch.size() < static_cast<size_t>(s.patches)) w.by_patch.resize(static_cast<size_t>(s.patches));
  for (auto& list : w.by_patch) list.clear();
  for (size_t i : among) w.by_patch[s.of[i]].push_back(i);
  return w.by_patch;
}

// The stacked counterpart of BestLine: candidate directions through two
// crossings of one patch, each scored by the inliers of its parallel lines
// over all patches; a direction must rest on at least two of the centre
// patch's crossings.
void BestParallelLines(const Stack& s, const std::vector<size_t>& among, double band, const EdgeLineOptions& o,
                       uint64_t seed, Work& w, ParallelBands& bands, Found* best) {
  best->Clear();
  const std::vector<std::vector<size_t>>& by_patch = ByPatch(s, among, w);
  if (by_patch[s.centre].size() < 2) return;
  // Candidates are scored by their counts; only a new best builds its
  // inlier list.
  for (double baseline : {1.0 / 3.0, 4.0 * band}) {
    Pcg32 rng(seed);
    int tried = 0;
    for (int draw = 0; draw < 8 * o.candidates && tried < o.candidates; ++draw) {
      const size_t a = among[rng.NextU32() % among.size()];
      const std::vector<size_t>& same = by_patch[s.of[a]];
      const size_t b = same[rng.NextU32() % same.size()];
      const double dx = s.m[b].x - s.m[a].x, dy = s.m[b].y - s.m[a].y, len = std::hypot(dx, dy);
      if (len < baseline) continue;
      ++tried;
      FindParallelBands(s, by_patch, -dy / len, dx / len, band, &bands);
      if (bands.centre < 2) continue;
      if (bands.total > best->inliers.size()) {
        best->ok = true;
        best->line = Line{0.0, 0.0, -dy / len, dx / len};
        BandInliers(bands, &best->inliers);
      }
    }
    if (best->ok) break;
  }
  if (!best->ok) return;
  for (int refine = 0; refine < 2 && best->inliers.size() >= 2; ++refine) {
    const Line l = FitParallel(s, best->inliers, w);
    FindParallelBands(s, by_patch, l.nx, l.ny, band, &bands);
    if (bands.centre < 2) break;
    best->line = l;
    BandInliers(bands, &best->inliers);
  }
}

// Steps 3-4 on k crossings, the first line and (with o.second) a second
// one on the crossings off it; best(among, seed, found) is the robust line
// search. With `near` (near(found, among, inliers): the crossings of `among`
// within the band of a found line or lines), a corner's first line is fitted
// again off the second's band.
template <class Best, class Near>
void FindLines(size_t k, const EdgeLineOptions& o, uint64_t seed, const Best& best, const Near* near, Work& w,
               DirectionEstimate* out) {
  char reason[128];
  w.all.resize(k);
  for (size_t i = 0; i < k; ++i) w.all[i] = i;
  Found& first = w.first;
  best(w.all, seed, &first);
  const double need = std::max<double>(o.min_crossings, o.min_share * k);
  if (!first.ok || first.inliers.size() < need) {
    std::snprintf(reason, sizeof(reason), "no straight edge: %zu of %zu crossings on one line", first.inliers.size(), k);
    NoLines(reason, out);
    return;
  }
  SetLobe(first, k, &out->first);
  if (!o.second) return;
  w.flags.assign(k, 0);
  for (size_t i : first.inliers) w.flags[i] = 1;
  w.rest.clear();
  for (size_t i = 0; i < k; ++i) {
    if (!w.flags[i]) w.rest.push_back(i);
  }
  Found& second = w.second;
  best(w.rest, HashCombine(seed, 2), &second);
  const double need2 = std::max<double>(o.min_crossings, o.second_min_share * k);
  if (!second.ok || second.inliers.size() < need2) {
    std::snprintf(reason, sizeof(reason), "no second edge: %zu of %zu crossings on a second line",
                  second.inliers.size(), k);
    SetNone(reason, &out->second);
  } else if (AxialDistanceDeg(NormalDegrees(second.line), out->first.theta_deg) < o.min_separation_deg) {
    SetNone("the second line is parallel to the first", &out->second);
  } else {
    SetLobe(second, k, &out->second);
    if (near == nullptr) return;
    // A corner: each edge is a half-line, and the crossings near the vertex
    // lie in both bands; the first line took them all, and they pull its
    // direction towards the second edge. Its direction is fitted again on
    // the crossings off the second line's band (the second line never had
    // them), kept if the refit is nearer the first edge than the second.
    // Measured on the shadow scene's stacked fits
    // (bench/results/render_corner_refit.md): the first direction's median
    // error on two-edge pixels 1.3-1.6 -> 0.5-0.7 degrees at N = 4096, and
    // the aligned lattices' edge error 2.4-3.5% lower at N = 256, 1024 and
    // 4096 over twelve scene seeds; on the image-plane pooled fit
    // (antialias) the same refit moved the edge error by -3% to +2%, so
    // that fit, and a single patch's, keep the first line as found.
    (*near)(second, w.all, &w.near);
    w.flags.assign(k, 0);
    for (size_t i : w.near) w.flags[i] = 1;
    w.off.clear();
    for (size_t i = 0; i < k; ++i) {
      if (!w.flags[i]) w.off.push_back(i);
    }
    Found& refit = w.refit;
    best(w.off, seed, &refit);
    if (refit.ok && refit.inliers.size() >= static_cast<size_t>(o.min_crossings) &&
        AxialDistanceDeg(NormalDegrees(refit.line), out->first.theta_deg) <
            AxialDistanceDeg(NormalDegrees(refit.line), out->second.theta_deg)) {
      out->first.theta_deg = out->first.fit_theta_deg = NormalDegrees(refit.line);
    }
  }
}

Status ValidateOptions(const EdgeLineOptions& o) {
  if (!(o.neighbour_radius >= 0.5 && o.neighbour_radius <= 5.0)) {
    return Status::InvalidArgument("edge lines: neighbour_radius must be in [0.5, 5] spacings");
  }
  if (!(o.jump_fraction > 0.0 && o.jump_fraction < 1.0)) {
    return Status::InvalidArgument("edge lines: jump_fraction must be in (0, 1)");
  }
  if (!(o.band > 0.0 && o.band <= 5.0)) return Status::InvalidArgument("edge lines: band must be in (0, 5]");
  if (o.min_crossings < 2) return Status::InvalidArgument("edge lines: min_crossings must be at least 2");
  if (!(o.min_share >= 0.0 && o.min_share <= 1.0) ||
      !(o.second_min_share >= 0.0 && o.second_min_share <= 1.0)) {
    return Status::InvalidArgument("edge lines: shares must be in [0, 1]");
  }
  if (o.candidates < 1 || o.candidates > 100000) {
    return Status::InvalidArgument("edge lines: candidates must be in [1, 100000]");
  }
  if (!(o.min_separation_deg >= 0.0 && o.min_separation_deg <= 90.0)) {
    return Status::InvalidArgument("edge lines: min_separation_deg must be in [0, 90]");
  }
  if (o.focus && !(o.focus_x0 >= 0.0 && o.focus_x0 < o.focus_x1 && o.focus_x1 <= 1.0 &&
                   o.focus_y0 >= 0.0 && o.focus_y0 < o.focus_y1 && o.focus_y1 <= 1.0)) {
    return Status::InvalidArgument("edge lines: the focus box must be a non-empty box inside [0,1]^2");
  }
  return Status::Ok();
}

bool NonConstant(const SampledPatch& patch) {
  const auto [lo, hi] = std::minmax_element(patch.values.begin(), patch.values.end());
  return *hi - *lo > 1e-12 * std::max(1.0, std::fabs(*hi));
}

// Steps 1-2: the midpoints of the neighbouring pairs whose values jump.
void Crossings(const SampledPatch& patch, const EdgeLineOptions& o, Work& w, std::vector<Point2>* mid) {
  const std::vector<Point2>& p = patch.points;
  const std::vector<double>& v = patch.values;
  const size_t n = p.size();
  const auto [lo, hi] = std::minmax_element(v.begin(), v.end());
  const double range = *hi - *lo;
  const double spacing = 1.0 / std::sqrt(static_cast<double>(n));
  const double radius = o.neighbour_radius * spacing, jump = o.jump_fraction * range;

  // Neighbouring pairs through a bucket grid of cells no smaller than the
  // radius (so the 3 x 3 cells around a point hold all its neighbours): a
  // counting sort of the points by cell, each cell's points in index order.
  const int g = std::max(1, static_cast<int>(std::floor(1.0 / radius)));
  auto cell = [g](double t) { return std::min(g - 1, std::max(0, static_cast<int>(t * g))); };
  const size_t cells = static_cast<size_t>(g) * g;
  w.cell_start.assign(cells + 1, 0);
  w.cell_of.resize(n);
  for (size_t i = 0; i < n; ++i) {
    w.cell_of[i] = cell(p[i].y) * g + cell(p[i].x);
    ++w.cell_start[static_cast<size_t>(w.cell_of[i]) + 1];
  }
  for (size_t c = 0; c < cells; ++c) w.cell_start[c + 1] += w.cell_start[c];
  w.cell_fill.assign(w.cell_start.begin(), w.cell_start.end() - 1);
  w.cell_order.resize(n);
  for (size_t i = 0; i < n; ++i) w.cell_order[w.cell_fill[static_cast<size_t>(w.cell_of[i])]++] = static_cast<uint32_t>(i);
  mid->clear();
  for (size_t i = 0; i < n; ++i) {
    const int cx = cell(p[i].x), cy = cell(p[i].y);
    for (int y = std::max(0, cy - 1); y <= std::min(g - 1, cy + 1); ++y) {
      for (int x = std::max(0, cx - 1); x <= std::min(g - 1, cx + 1); ++x) {
        const size_t c = static_cast<size_t>(y * g + x);
        for (uint32_t at = w.cell_start[c]; at < w.cell_start[c + 1]; ++at) {
          const uint32_t j = w.cell_order[at];
          if (j <= i) continue;
          const double dx = p[j].x - p[i].x, dy = p[j].y - p[i].y;
          if (dx * dx + dy * dy >= radius * radius) continue;
          if (std::fabs(v[j] - v[i]) < jump) continue;
          mid->push_back({0.5 * (p[i].x + p[j].x), 0.5 * (p[i].y + p[j].y)});
        }
      }
    }
  }
}

}  // namespace

struct EdgeLineScratch::Impl {
  Work work;
  PatchCrossings own;     // a patch's crossings, for the fits of one patch
  SampledPatch pooled;    // the pooled patch of EstimateEdgeLinesPooled
  Stack stack;            // the stacked crossings of EstimateEdgeLinesStacked
  ParallelBands bands, near_bands;
};

EdgeLineScratch::EdgeLineScratch() : impl_(std::make_unique<Impl>()) {}
EdgeLineScratch::~EdgeLineScratch() = default;
EdgeLineScratch::EdgeLineScratch(EdgeLineScratch&&) noexcept = default;
EdgeLineScratch& EdgeLineScratch::operator=(EdgeLineScratch&&) noexcept = default;

void EdgeLineScratch::Reserve(size_t points, size_t crossings, size_t patches) {
  Work& w = impl_->work;
  for (auto* v : {&w.cell_start, &w.cell_fill, &w.cell_order}) v->reserve(points + 1);
  w.cell_of.reserve(points);
  for (auto* v : {&w.all, &w.rest, &w.off, &w.near, &w.anchors, &w.candidate, &w.first.inliers, &w.second.inliers,
                  &w.refit.inliers}) {
    v->reserve(crossings);
  }
  w.flags.reserve(crossings);
  if (w.by_patch.size() < patches) w.by_patch.resize(patches);
  for (auto& list : w.by_patch) list.reserve(crossings);
  for (auto* v : {&w.cx, &w.cy, &w.count}) v->reserve(patches);
  impl_->own.midpoints.reserve(crossings);
  impl_->pooled.points.reserve(points);
  impl_->pooled.values.reserve(points);
  impl_->stack.m.reserve(crossings);
  impl_->stack.of.reserve(crossings);
  for (ParallelBands* b : {&impl_->bands, &impl_->near_bands}) {
    b->sorted.reserve(crossings);
    for (auto* v : {&b->begin, &b->first, &b->count}) v->reserve(patches);
  }
}

Status FindCrossings(const SampledPatch& patch, const EdgeLineOptions& o, EdgeLineScratch& scratch,
                     PatchCrossings* out) {
  if (Status s = ValidateSampledPatch(patch); !s.ok()) return s;
  if (Status s = ValidateOptions(o); !s.ok()) return s;
  out->samples = patch.points.size();
  out->constant = !NonConstant(patch);
  out->midpoints.clear();
  if (!out->constant) Crossings(patch, o, scratch.impl().work, &out->midpoints);
  return Status::Ok();
}

Status EstimateEdgeLines(const SampledPatch& patch, const EdgeLineOptions& o, EdgeLineScratch& scratch,
                         DirectionEstimate* out) {
  PatchCrossings& c = scratch.impl().own;
  if (Status s = FindCrossings(patch, o, scratch, &c); !s.ok()) return s;
  return EstimateEdgeLines(c, o, scratch, out);
}

Status EstimateEdgeLines(const PatchCrossings& c, const EdgeLineOptions& o, EdgeLineScratch& scratch,
                         DirectionEstimate* out) {
  if (c.samples == 0) return Status::InvalidArgument("edge lines: the crossings of an empty patch");
  if (Status s = ValidateOptions(o); !s.ok()) return s;
  Reset(out);
  out->has_second = o.second;
  const size_t n = c.samples;
  if (c.constant) {
    NoLines("constant patch", out);
    return Status::Ok();
  }
  const double spacing = 1.0 / std::sqrt(static_cast<double>(n));
  const std::vector<Point2>& mid = c.midpoints;
  const size_t k = mid.size();
  out->frequencies = k;
  if (k < static_cast<size_t>(o.min_crossings)) {
    char reason[96];
    std::snprintf(reason, sizeof(reason), "no edge: %zu neighbouring pairs jump", k);
    NoLines(reason, out);
    return Status::Ok();
  }
  const double band = o.band * spacing;
  const uint64_t seed = HashCombine(static_cast<uint64_t>(n), static_cast<uint64_t>(k));
  Work& w = scratch.impl().work;
  using NoNear = void (*)(const Found&, const std::vector<size_t>&, std::vector<size_t>*);
  FindLines(
      k, o, seed,
      [&](const std::vector<size_t>& among, uint64_t s, Found* found) { BestLine(mid, among, band, o, s, w, found); },
      static_cast<const NoNear*>(nullptr), w, out);
  return Status::Ok();
}

Status EstimateEdgeLinesPooled(const std::array<const SampledPatch*, 9>& pixels, double margin,
                               const EdgeLineOptions& options, EdgeLineScratch& scratch, DirectionEstimate* out) {
  const SampledPatch* centre = pixels[4];
  if (!centre || centre->points.empty()) return Status::InvalidArgument("pooled edge lines: no centre pixel");
  if (!(margin > 0.0 && margin <= 1.0)) return Status::InvalidArgument("pooled edge lines: margin must be in (0, 1]");
  const double side = 1.0 + 2.0 * margin;
  SampledPatch& pooled = scratch.impl().pooled;
  pooled.points.clear();
  pooled.values.clear();
  for (int k = 0; k < 9; ++k) {
    const SampledPatch* p = pixels[k];
    if (!p) continue;
    if (p->values.size() != p->points.size()) {
      return Status::InvalidArgument("pooled edge lines: a patch's values do not match its points");
    }
    const int dx = k % 3 - 1, dy = k / 3 - 1;
    for (size_t j = 0; j < p->points.size(); ++j) {
      const double u = p->points[j].x + dx, v = p->points[j].y + dy;
      if (u < -margin || u > 1.0 + margin || v < -margin || v > 1.0 + margin) continue;
      pooled.points.push_back({(u + margin) / side, (v + margin) / side});
      pooled.values.push_back(p->values[j]);
    }
  }
  EdgeLineOptions o = options;
  o.focus = true;
  const double inset = kPooledFocusInset / std::sqrt(static_cast<double>(centre->points.size()));
  o.focus_x0 = o.focus_y0 = (margin + inset) / side;
  o.focus_x1 = o.focus_y1 = (1.0 + margin - inset) / side;
  return EstimateEdgeLines(pooled, o, scratch, out);
}

Status EstimateEdgeLinesStacked(std::span<const PatchCrossings* const> pixels, const EdgeLineOptions& o,
                                EdgeLineScratch& scratch, DirectionEstimate* out) {
  const size_t count = pixels.size();
  const size_t side = static_cast<size_t>(std::lround(std::sqrt(static_cast<double>(count))));
  if (side * side != count || side % 2 == 0) {
    return Status::InvalidArgument("stacked edge lines: the block must be an odd square (3 x 3, 5 x 5, ...), got " +
                                   std::to_string(count) + " pixels");
  }
  const int centre_index = static_cast<int>(count / 2);
  const PatchCrossings* centre = pixels[static_cast<size_t>(centre_index)];
  if (!centre || centre->samples == 0) return Status::InvalidArgument("stacked edge lines: no centre pixel");
  if (Status s = ValidateOptions(o); !s.ok()) return s;
  for (const PatchCrossings* p : pixels) {
    if (p && p->samples != centre->samples) {
      return Status::InvalidArgument("stacked edge lines: every pixel needs as many samples as the centre");
    }
  }
  Reset(out);
  out->has_second = o.second;
  if (centre->constant) {
    NoLines("constant patch", out);
    return Status::Ok();
  }
  EdgeLineScratch::Impl& x = scratch.impl();
  Stack& s = x.stack;
  s.m.clear();
  s.of.clear();
  s.patches = static_cast<int>(count);
  s.centre = centre_index;
  for (size_t k = 0; k < count; ++k) {
    if (!pixels[k] || pixels[k]->constant) continue;
    for (const Point2& m : pixels[k]->midpoints) {
      s.m.push_back(m);
      s.of.push_back(static_cast<int>(k));
    }
  }
  const size_t k = s.m.size();
  out->frequencies = k;
  const size_t own = static_cast<size_t>(std::count(s.of.begin(), s.of.end(), s.centre));
  if (own < 2 || k < static_cast<size_t>(o.min_crossings)) {
    char reason[96];
    std::snprintf(reason, sizeof(reason), "no edge: %zu neighbouring pairs jump in the pixel", own);
    NoLines(reason, out);
    return Status::Ok();
  }
  const double band = o.band / std::sqrt(static_cast<double>(centre->samples));
  const uint64_t seed = HashCombine(static_cast<uint64_t>(centre->samples), static_cast<uint64_t>(k));
  Work& w = x.work;
  const auto near = [&](const Found& f, const std::vector<size_t>& among, std::vector<size_t>* inliers) {
    FindParallelBands(s, ByPatch(s, among, w), f.line.nx, f.line.ny, band, &x.near_bands);
    BandInliers(x.near_bands, inliers);
  };
  FindLines(
      k, o, seed,
      [&](const std::vector<size_t>& among, uint64_t sd, Found* found) {
        BestParallelLines(s, among, band, o, sd, w, x.bands, found);
      },
      &near, w, out);
  return Status::Ok();
}

// The calls that return their results, each with a scratch of its own.

StatusOr<PatchCrossings> FindCrossings(const SampledPatch& patch, const EdgeLineOptions& o) {
  EdgeLineScratch scratch;
  PatchCrossings c;
  if (Status s = FindCrossings(patch, o, scratch, &c); !s.ok()) return s;
  return c;
}

StatusOr<DirectionEstimate> EstimateEdgeLines(const SampledPatch& patch, const EdgeLineOptions& o) {
  EdgeLineScratch scratch;
  DirectionEstimate out;
  if (Status s = EstimateEdgeLines(patch, o, scratch, &out); !s.ok()) return s;
  return out;
}

StatusOr<DirectionEstimate> EstimateEdgeLines(const PatchCrossings& c, const EdgeLineOptions& o) {
  EdgeLineScratch scratch;
  DirectionEstimate out;
  if (Status s = EstimateEdgeLines(c, o, scratch, &out); !s.ok()) return s;
  return out;
}

StatusOr<DirectionEstimate> EstimateEdgeLinesPooled(const std::array<const SampledPatch*, 9>& pixels,
                                                    double margin, const EdgeLineOptions& options) {
  EdgeLineScratch scratch;
  DirectionEstimate out;
  if (Status s = EstimateEdgeLinesPooled(pixels, margin, options, scratch, &out); !s.ok()) return s;
  return out;
}

StatusOr<DirectionEstimate> EstimateEdgeLinesStacked(const std::vector<const PatchCrossings*>& pixels,
                                                     const EdgeLineOptions& o) {
  EdgeLineScratch scratch;
  DirectionEstimate out;
  if (Status s = EstimateEdgeLinesStacked(std::span<const PatchCrossings* const>(pixels), o, scratch, &out); !s.ok()) {
    return s;
  }
  return out;
}

StatusOr<DirectionEstimate> EstimateEdgeLinesStacked(const std::vector<const SampledPatch*>& pixels,
                                                     const EdgeLineOptions& o) {
  const size_t count = pixels.size();
  std::vector<PatchCrossings> found(count);
  std::vector<const PatchCrossings*> block(count, nullptr);
  for (size_t k = 0; k < count; ++k) {
    if (!pixels[k]) continue;
    StatusOr<PatchCrossings> c = FindCrossings(*pixels[k], o);
    if (!c.ok()) return c.status();
    found[k] = std::move(*c);
    block[k] = &found[k];
  }
  return EstimateEdgeLinesStacked(block, o);
}

StatusOr<DirectionEstimate> EstimateEdgeLinesStacked(const std::array<const SampledPatch*, 9>& pixels,
                                                     const EdgeLineOptions& o) {
  return EstimateEdgeLinesStacked(std::vector<const SampledPatch*>(pixels.begin(), pixels.end()), o);
}

}  // namespace alignset

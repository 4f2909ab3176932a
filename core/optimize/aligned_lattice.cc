#include "core/optimize/aligned_lattice.h"

#include <algorithm>
#include <atomic>
#include <iterator>
#include <limits>
#include <memory>
#include <tuple>
#include <thread>
#include <cmath>
#include <complex>
#include <functional>
#include <numeric>
#include <string>
#include <utility>

#include "core/analysis/convex_polygon.h"
#include "core/analysis/folded_indicator_spectrum.h"
#include "core/analysis/integer_indicator_spectrum.h"
#include "core/analysis/lattice_variance.h"
#include "core/optimize/lattice_term_cache.h"
#include "core/optimize/optimizer.h"
#include "core/spectral/direction_budget.h"
#include "core/util/angles.h"
#include "core/util/hash.h"

namespace alignset {
namespace {

// Offsets of the scored edges from the centre, along their normal: one
// through the centre and two that cut the square unevenly.
constexpr double kEdgeOffsets[] = {0.0, 0.21, -0.33};
// A folded lattice's variance swings by up to 10x between offsets a tenth
// apart (the four folded copies of the edge move against each other), so it
// scores six, all of them in both stages. Positive only: the point
// reflection about the centre takes an edge at -o to the complement of the
// edge at o, which a folded set integrates with the same error; and not 0,
// which every folded rank-1 lattice with N even integrates exactly (the
// coefficients with h_x + h_y even vanish there, and so does every dual
// point's parity).
constexpr double kFoldedEdgeOffsets[] = {0.03, 0.08, 0.13, 0.19, 0.26, 0.33};
size_t CoarseOffsets(bool folded) { return folded ? std::size(kFoldedEdgeOffsets) : 2; }
size_t FullOffsets(bool folded) { return folded ? std::size(kFoldedEdgeOffsets) : std::size(kEdgeOffsets); }
constexpr double kCornerWeight = 0.5;
// The window is sampled at 2 kWindowSteps + 1 angles; a folded lattice's at
// twice as many (its resonances are narrower than a quarter of its default
// window).
constexpr int kWindowSteps = 4;
int WindowSteps(bool folded) { return folded ? 2 * kWindowSteps : kWindowSteps; }
constexpr uint32_t kFullSearchLimit = 65536;
// A family's coefficient tables may take this much memory (a two-direction
// family at N = 32768 takes 56 MB); above it the vertices' factors are
// computed on the spot.
constexpr double kMaxTableBytes = 64e6;

struct Family {
  // Each scored edge is `parts` consecutive spectra: 1, or 2 of the 4
  // copies of a folded edge (TentFoldedHalf: the other two are their
  // conjugates, SymmetricUnionEnergy).
  std::vector<IntegerIndicatorSpectrum> spectra;
  size_t parts = 1;
  std::vector<size_t> ends;  // direction i's edges are [ends[i - 1], ends[i])
  size_t Edges() const { return spectra.size() / parts; }
};

// The edges scored: for each direction, 2 steps + 1 normals across the
// window, each through `offsets` of the kEdgeOffsets (kFoldedEdgeOffsets);
// the polygons alone (a key's score divides by their count, which a cached
// search needs without the tables).
std::vector<std::vector<Polygon>> ScoredPolygons(const std::vector<double>& directions_deg,
                                                 double window_deg, int steps, size_t offsets, bool folded) {
  std::vector<std::vector<Polygon>> out;
  for (double d : directions_deg) {
    std::vector<Polygon>& polygons = out.emplace_back();
    for (int k = -steps; k <= steps; ++k) {
      const double delta = window_deg * k / steps;
      const Vec2 n = UnitVector(d + delta);
      for (size_t o = 0; o < offsets; ++o) {
        const double offset = folded ? kFoldedEdgeOffsets[o] : kEdgeOffsets[o];
        const double c = 0.5 * (n.x + n.y) + offset;
        Polygon p = ClipHalfPlane(UnitSquarePolygon(), n, c);
        if (SignedArea(p) > 1e-12) polygons.push_back(std::move(p));
      }
    }
  }
  return out;
}

// The same edges with their coefficients tabulated for the dual points
// within `radius`.
Family ScoredFamily(const std::vector<double>& directions_deg, double window_deg, int steps,
                    size_t offsets, int radius, bool folded) {
  const size_t parts = folded ? 2 : 1;
  // Each edge's square has two vertices off the corners, one table each (a
  // folded edge's two copies up to five each).
  const double bytes = static_cast<double>(directions_deg.size()) * (2 * steps + 1) * offsets *
                       (folded ? 10.0 : 2.0) * (2.0 * radius + 1.0) * sizeof(std::complex<double>);
  const bool tabulate = bytes <= kMaxTableBytes;
  Family f;
  f.parts = parts;
  for (const std::vector<Polygon>& polygons : ScoredPolygons(directions_deg, window_deg, steps, offsets, folded)) {
    for (const Polygon& p : polygons) {
      if (folded) {
        for (const Polygon& q : TentFoldedHalf(p)) f.spectra.emplace_back(q, radius, tabulate);
      } else {
        f.spectra.emplace_back(p, radius, tabulate);
      }
    }
    f.ends.push_back(f.spectra.size() / parts);
  }
  return f;
}

// x^2's cosine coefficient int x^2 cos(pi k x) dx on [0, 1].
double SquareCosine(int k) {
  if (k == 0) return 1.0 / 3.0;
  const double sign = (k % 2 == 0) ? 1.0 : -1.0;
  return 2.0 * sign / (kPi * kPi * static_cast<double>(k) * k);
}

// The terms of one generator's score over the dual points within `radius`:
// per direction of the family, the sum of its edges' log variances, and
// kCornerWeight times the log variance of the corner term. A key's score is
// the mean log variance of its edges plus the corner term (Combine); kept
// per direction, the first stage's terms serve every key a direction is in.
struct Terms {
  std::vector<double> directions;
  double corner = 0.0;
};

Terms ScoreTerms(uint32_t n, uint32_t g, int radius, const Family& family) {
  const std::vector<Frequency> dual = Rank1DualHalfDisk(n, g, radius);
  const size_t edges = family.Edges();
  std::vector<double> edge_sum(edges, 0.0);
  double corner = 0.0;
  // Edge by edge over the dual points, so that one edge's tables stay in
  // cache (a folded family's tables take tens of MB; each sum adds its
  // terms in the dual's order either way).
  for (size_t k = 0; k < edges; ++k) {
    double sum = 0.0;
    if (family.parts == 1) {
      for (const Frequency& h : dual) sum += family.spectra[k].Energy(h.a, h.b);
    } else {
      const IntegerIndicatorSpectrum* edge = &family.spectra[k * family.parts];
      for (const Frequency& h : dual) sum += SymmetricUnionEnergy(edge, family.parts, h.a, h.b);
    }
    edge_sum[k] = sum;
  }
  for (const Frequency& h : dual) {
    const double hx = h.a, hy = h.b;
    if (family.parts == 1) {
      // (x - 1/2)(y - 1/2): coefficients i/(2 pi a) * i/(2 pi b) off the axes.
      if (h.a != 0 && h.b != 0) corner += 1.0 / (16.0 * std::pow(kPi, 4) * hx * hx * hy * hy);
    } else {
      const double c = SquareCosine(h.a) * SquareCosine(h.b);
      corner += c * c;
    }
  }
  // Each half-disk point stands for +-h: the factor 2 keeps these variances.
  // The floor, a tenth of what a good lattice reaches (about 0.3 / N^2), keeps
  // one member that a degenerate lattice integrates exactly (g = 1 and the
  // edge through the centre at 45 degrees: its dual misses that edge's
  // coefficients, while the set is a line) from outweighing all others.
  const double floor = 0.1 / (static_cast<double>(n) * n);
  Terms t;
  size_t k = 0;
  for (size_t end : family.ends) {
    double sum = 0.0;
    if (family.parts == 1) {
      for (; k < end; ++k) sum += std::log(2.0 * edge_sum[k] + floor);
    } else {
      // A folded lattice's variance swings by 4x between neighbouring
      // normals of the window (its two strips make resonances a plain
      // lattice does not have); the log of the mean, counted once per edge
      // (Combine divides by the count), lets no member of the window hide a
      // bad one.
      const size_t first = k;
      double mean = 0.0;
      for (; k < end; ++k) mean += 2.0 * edge_sum[k];
      const double count = static_cast<double>(end - first);
      sum = count * std::log(mean / std::max(1.0, count) + floor);
    }
    t.directions.push_back(sum);
  }
  // A folded lattice integrates the smooth corner term like N^-4, far below
  // the edges' floor; its own floor, 1e-3 / N^3, is where the lattice is
  // already far better than Owen-Sobol's N^-3 on smooth functions: below it
  // the edges decide.
  const double corner_floor = family.parts == 1 ? floor : 1e-3 / (static_cast<double>(n) * n * n);
  t.corner = kCornerWeight * std::log(2.0 * corner + corner_floor);
  return t;
}

// A score rounded to 2^-30 (about 1e-9; scores are logs near -10...-40):
// generators a symmetry makes equally good (a direction and its mirror
// about 45 degrees swap g and its inverse) differ by rounding alone, in the
// last digits, and rounding must not be what picks one; rounded, they tie
// and the smaller g wins, as the header promises.
double Quantized(double score) { return std::ldexp(std::nearbyint(std::ldexp(score, 30)), -30); }

// fn(i) for i in [0, count) on `threads` threads (0: all cores), each
// thread given at least `grain` items (a thread costs tens of microseconds
// to start); each result depends on its i alone, so nothing depends on the
// thread count.
// `passed(fraction)`, when given, is called on the calling thread only (a
// progress display need not be thread-safe), each time another 1/200 of the
// items is done, as far as that thread sees.
template <class Fn>
void ParallelOver(size_t count, int threads, size_t grain, const Fn& fn,
                  const std::function<void(double fraction)>& passed = {}) {
  size_t workers = threads > 0 ? static_cast<size_t>(threads)
                               : std::max(1u, std::thread::hardware_concurrency());
  workers = std::min(workers, std::max<size_t>(1, count / grain));
  std::atomic<size_t> next{0};
  std::atomic<size_t> completed{0};
  size_t reported = 0;  // in 1/200ths, the calling thread's
  auto work = [&](bool caller) {
    for (size_t i = next++; i < count; i = next++) {
      fn(i);
      const size_t c = ++completed;
      if (caller && passed && c * 200 / count > reported) {
        reported = c * 200 / count;
        passed(static_cast<double>(c) / static_cast<double>(count));
      }
    }
  };
  std::vector<std::thread> pool;
  for (size_t t = 1; t < workers; ++t) pool.emplace_back(work, false);
  work(true);
  for (std::thread& t : pool) t.join();
}

// A key's score from its directions' terms (in the key's order) and the
// count of its edges.
double Combine(const std::vector<double>& direction_sums, size_t edges, double corner) {
  double sum = 0.0;
  for (double x : direction_sums) sum += x;
  return Quantized(sum / static_cast<double>(std::max<size_t>(1, edges)) + corner);
}

Status Validate(uint32_t n, const std::vector<double>& directions, const AlignedLatticeOptions& o) {
  if (n < kMinPoints || n > kMaxPoints) {
    return Status::InvalidArgument("aligned lattice: N must be in [" + std::to_string(kMinPoints) +
                                   ", " + std::to_string(kMaxPoints) + "], got " +
                                   std::to_string(n));
  }
  if (directions.empty() || directions.size() > static_cast<size_t>(kMaxArbitraryDirections)) {
    return Status::InvalidArgument("aligned lattice: 1 to " +
                                   std::to_string(kMaxArbitraryDirections) +
                                   " directions, got " + std::to_string(directions.size()));
  }
  for (double d : directions) {
    if (!std::isfinite(d)) return Status::InvalidArgument("aligned lattice: a direction is not finite");
  }
  if (!(o.window_deg >= 0.0 && o.window_deg <= 10.0)) {
    return Status::InvalidArgument("aligned lattice: window_deg must be in [0, 10]");
  }
  if (o.threads < 0) return Status::InvalidArgument("aligned lattice: threads must be >= 0");
  if (o.finalists < 1) return Status::InvalidArgument("aligned lattice: finalists must be >= 1");
  return Status::Ok();
}

// The two stages' radii: all dual points within N / 2 in the final one,
// within 8 sqrt(N) (at least 32) in the first.
int FullRadius(uint32_t n) { return static_cast<int>(n / 2); }
int FirstRadius(uint32_t n) {
  return std::min(FullRadius(n), std::max(32, static_cast<int>(std::lround(8.0 * std::sqrt(n)))));
}

// The generators the first stage scores: every g coprime to N, a stride
// subset above kFullSearchLimit.
std::vector<uint32_t> SearchCandidates(uint32_t n) {
  const uint32_t stride = n > kFullSearchLimit ? (n + kFullSearchLimit - 1) / kFullSearchLimit : 1;
  std::vector<uint32_t> candidates;
  for (uint32_t g = 1; g < n; g += stride) {
    if (std::gcd(g, n) == 1) candidates.push_back(g);
  }
  return candidates;
}

size_t CoarseEdgeCount(double direction, const AlignedLatticeOptions& options) {
  return ScoredPolygons({direction}, options.window_deg, 1, CoarseOffsets(options.folded), options.folded)
      .front()
      .size();
}

// One direction's first-stage terms for every candidate, from the cache or
// computed into it.
std::shared_ptr<const std::vector<LatticeTermCache::Terms>> CoarseTerms(
    uint32_t n, double direction, const AlignedLatticeOptions& options, const std::vector<uint32_t>& candidates,
    LatticeTermCache* cache, const std::function<void(double)>& within_pass) {
  const LatticeTermCache::Key key{n, LatticeTermCache::Stage::kCoarse, options.window_deg, direction, options.folded};
  if (auto held = cache->FindDense(key)) return held;
  const Family f =
      ScoredFamily({direction}, options.window_deg, 1, CoarseOffsets(options.folded), FirstRadius(n), options.folded);
  auto terms = std::make_shared<std::vector<LatticeTermCache::Terms>>(candidates.size());
  ParallelOver(
      candidates.size(), options.threads, 16,
      [&](size_t j) {
        const Terms t = ScoreTerms(n, candidates[j], FirstRadius(n), f);
        (*terms)[j] = {t.directions.front(), t.corner};
      },
      within_pass);
  cache->PutDense(key, terms);
  return terms;
}

}  // namespace

StatusOr<std::vector<double>> AlignedLatticeScores(uint32_t n, std::span<const uint32_t> generators,
                                                  const std::vector<double>& directions_deg,
                                                  const AlignedLatticeOptions& options) {
  if (Status s = Validate(n, directions_deg, options); !s.ok()) return s;
  for (uint32_t g : generators) {
    if (g == 0 || g >= n || std::gcd(g, n) != 1) {
      return Status::InvalidArgument("aligned lattice: g = " + std::to_string(g) +
                                     " is not a generator coprime to N = " + std::to_string(n));
    }
  }
  const int r_full = FullRadius(n), r_first = FirstRadius(n);
  const bool folded = options.folded;
  const Family family = r_full > r_first ? ScoredFamily(directions_deg, options.window_deg, WindowSteps(folded),
                                                        FullOffsets(folded), r_full, folded)
                                         : ScoredFamily(directions_deg, options.window_deg, 1,
                                                        CoarseOffsets(folded), r_first, folded);
  std::vector<double> scores(generators.size());
  ParallelOver(generators.size(), options.threads, std::max<size_t>(1, 4096 / n), [&](size_t j) {
    const Terms t = ScoreTerms(n, generators[j], r_full, family);
    scores[j] = Combine(t.directions, family.Edges(), t.corner);
  });
  return scores;
}

StatusOr<double> AlignedLatticeScore(uint32_t n, uint32_t g, const std::vector<double>& directions_deg,
                                     const AlignedLatticeOptions& options) {
  const uint32_t one[] = {g};
  auto scores = AlignedLatticeScores(n, one, directions_deg, options);
  if (!scores.ok()) return scores.status();
  return scores->front();
}

StatusOr<std::vector<AlignedLatticeChoice>> ChooseAlignedLatticeGenerators(
    uint32_t n, const std::vector<std::vector<double>>& keys, const AlignedLatticeOptions& options,
    const std::function<void(double done, double total)>& progress) {
  for (const std::vector<double>& key : keys) {
    if (Status s = Validate(n, key, options); !s.ok()) return s;
  }
  // Without a cache of the caller's, one for this search alone: every term
  // goes through a cache either way, so a search with one computes what a
  // search without one does, to the bit.
  std::unique_ptr<LatticeTermCache> own;
  LatticeTermCache* cache = options.cache;
  if (!cache) {
    own = std::make_unique<LatticeTermCache>(std::numeric_limits<size_t>::max());
    cache = own.get();
  }
  using Key = LatticeTermCache::Key;
  const bool folded = options.folded;
  using Stage = LatticeTermCache::Stage;
  const int r_full = FullRadius(n);
  const int r_first = FirstRadius(n);
  const std::vector<uint32_t> candidates = SearchCandidates(n);
  // The first stage sees a coarse family (the window's ends and middle, two
  // offsets): it only has to keep the finalists, and it scores every g. Its
  // terms are kept per direction, each computed once however many keys
  // share it (a render's pairs share their degrees).
  std::vector<double> directions;
  for (const std::vector<double>& key : keys) directions.insert(directions.end(), key.begin(), key.end());
  std::sort(directions.begin(), directions.end());
  directions.erase(std::unique(directions.begin(), directions.end()), directions.end());
  const double total = static_cast<double>(r_full > r_first ? 2 * directions.size() : directions.size());
  double done = 0.0;
  // Within a direction's pass: a search at large N spends seconds to
  // minutes in one (N = 65536, tent-folded: about 20 s on two cores).
  std::function<void(double)> within_pass;
  // A pass's end is reported as done + 1 below.
  if (progress) {
    within_pass = [&](double fraction) {
      if (fraction < 1.0) progress(done + fraction, total);
    };
  }
  using Held = LatticeTermCache::Terms;
  std::vector<std::shared_ptr<const std::vector<Held>>> coarse(directions.size());
  std::vector<size_t> coarse_edges(directions.size());
  for (size_t i = 0; i < directions.size(); ++i) {
    coarse_edges[i] = CoarseEdgeCount(directions[i], options);
    coarse[i] = CoarseTerms(n, directions[i], options, candidates, cache, within_pass);
    if (progress) progress(++done, total);
  }
  // Each key's directions as indices into `directions`.
  std::vector<std::vector<size_t>> key_at(keys.size());
  for (size_t k = 0; k < keys.size(); ++k) {
    for (double d : keys[k]) {
      key_at[k].push_back(
          static_cast<size_t>(std::lower_bound(directions.begin(), directions.end(), d) - directions.begin()));
    }
  }
  // Each key's finalists by the first stage.
  std::vector<std::vector<std::pair<double, uint32_t>>> finalists(keys.size());
  for (size_t k = 0; k < keys.size(); ++k) {
    const std::vector<size_t>& at = key_at[k];
    std::vector<std::pair<double, uint32_t>>& ranked = finalists[k];
    ranked.resize(candidates.size());
    size_t edges = 0;
    for (size_t di : at) edges += coarse_edges[di];
    std::vector<double> sums(at.size());
    for (size_t j = 0; j < candidates.size(); ++j) {
      for (size_t i = 0; i < at.size(); ++i) sums[i] = (*coarse[at[i]])[j].edges;
      // The corner term is the same in every direction's pass.
      ranked[j] = {Combine(sums, edges, (*coarse[at[0]])[j].corner), candidates[j]};
    }
    const size_t keep = std::min(ranked.size(), static_cast<size_t>(options.finalists));
    std::partial_sort(ranked.begin(), ranked.begin() + keep, ranked.end());
    ranked.resize(keep);
  }
  // The final stage on the whole family, its terms also per direction: each
  // (direction, g) a key's finalists need is scored once, one direction's
  // family at a time (at N = 4096 a direction's tables take 3.5 MB).
  if (r_full > r_first) {
    std::vector<std::vector<uint32_t>> need(directions.size());
    for (size_t k = 0; k < keys.size(); ++k) {
      for (size_t di : key_at[k]) {
        for (const auto& entry : finalists[k]) need[di].push_back(entry.second);
      }
    }
    std::vector<std::vector<Held>> full(directions.size());
    std::vector<size_t> full_edges(directions.size());
    // A final term costs about N / 8 dual points times the family's edges
    // (milliseconds at N = 4096), so a key that misses a few of them, as a
    // key served one at a time does, still spreads them over the threads.
    const size_t final_grain = std::max<size_t>(1, 4096 / n);
    for (size_t i = 0; i < directions.size(); ++i) {
      std::vector<uint32_t>& gs = need[i];
      std::sort(gs.begin(), gs.end());
      gs.erase(std::unique(gs.begin(), gs.end()), gs.end());
      if (gs.empty()) {
        if (progress) progress(++done, total);
        continue;
      }
      full_edges[i] = ScoredPolygons({directions[i]}, options.window_deg, WindowSteps(folded), FullOffsets(folded), folded)
                          .front()
                          .size();
      const Key key{n, Stage::kFull, options.window_deg, directions[i], options.folded};
      std::vector<bool> found;
      cache->FindSparse(key, gs, &full[i], &found);
      std::vector<uint32_t> missing;
      for (size_t j = 0; j < gs.size(); ++j) {
        if (!found[j]) missing.push_back(gs[j]);
      }
      if (!missing.empty()) {
        // A caller's cache keeps the family's tables too: a key served alone
        // misses a few final terms of a direction the keys before it built
        // (a search's own cache would only hold every direction's at once).
        const Key family_key{n, Stage::kFullFamily, options.window_deg, directions[i], options.folded};
        auto family = options.cache ? std::static_pointer_cast<const Family>(cache->FindObject(family_key))
                                    : nullptr;
        if (!family) {
          auto built = std::make_shared<const Family>(
              ScoredFamily({directions[i]}, options.window_deg, WindowSteps(folded), FullOffsets(folded), r_full, folded));
          if (options.cache) {
            size_t bytes = 0;
            for (const IntegerIndicatorSpectrum& e : built->spectra) bytes += e.TableBytes();
            cache->PutObject(family_key, built, bytes);
          }
          family = std::move(built);
        }
        std::vector<Held> terms(missing.size());
        ParallelOver(
            missing.size(), options.threads, final_grain,
            [&](size_t j) {
              const Terms t = ScoreTerms(n, missing[j], r_full, *family);
              terms[j] = {t.directions.front(), t.corner};
            },
            within_pass);
        for (size_t j = 0, m = 0; j < gs.size(); ++j) {
          if (!found[j]) full[i][j] = terms[m++];
        }
        cache->PutSparse(key, missing, terms);
      }
      if (progress) progress(++done, total);
    }
    for (size_t k = 0; k < keys.size(); ++k) {
      const std::vector<size_t>& at = key_at[k];
      size_t edges = 0;
      for (size_t di : at) edges += full_edges[di];
      std::vector<double> sums(at.size());
      for (auto& entry : finalists[k]) {
        double corner = 0.0;
        for (size_t i = 0; i < at.size(); ++i) {
          const std::vector<uint32_t>& gs = need[at[i]];
          const Held& t = full[at[i]][static_cast<size_t>(std::lower_bound(gs.begin(), gs.end(), entry.second) - gs.begin())];
          sums[i] = t.edges;
          corner = t.corner;  // the same in every direction's pass
        }
        entry.first = Combine(sums, edges, corner);
      }
      std::sort(finalists[k].begin(), finalists[k].end());
    }
  }
  std::vector<AlignedLatticeChoice> choices;
  for (size_t k = 0; k < keys.size(); ++k) {
    AlignedLatticeChoice choice;
    choice.candidates = static_cast<uint32_t>(candidates.size());
    choice.generator = finalists[k].front().second;
    choice.score = finalists[k].front().first;
    choices.push_back(choice);
  }
  return choices;
}

StatusOr<AlignedLatticeChoice> ChooseAlignedLatticeGenerator(
    uint32_t n, const std::vector<double>& directions_deg, const AlignedLatticeOptions& options) {
  auto choices = ChooseAlignedLatticeGenerators(n, {directions_deg}, options);
  if (!choices.ok()) return choices.status();
  return choices->front();
}

StatusOr<PointSet> AlignedLattice(uint32_t n, const std::vector<double>& directions_deg,
                                  uint64_t seed, const AlignedLatticeOptions& options) {
  auto choice = ChooseAlignedLatticeGenerator(n, directions_deg, options);
  if (!choice.ok()) return choice.status();
  return LatticePoints(n, choice->generator, seed, options.folded);
}

}  // namespace alignset

#pragma once

#include <cmath>
#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <vector>

#include "core/util/point_set.h"
#include "core/util/status.h"

namespace alignset {

// An aligned rank-1 lattice: N points {frac(i (1, g) / N + shift)} whose
// generator g is chosen so that the lattice integrates step edges with
// normals near the requested directions well.
//
// Why a lattice: its spectrum is zero except on the dual lattice, N points
// per unit area spread evenly, so how far a strip along a direction stays
// dark is set by g and can grow like N; the optimized sets are dark only
// inside their frequency set, strips of length about sqrt(N)
// (lattice_variance.h has the exact variance).
//
// How g is chosen: every g coprime to N (a stride subset above 65536 points)
// is scored by the exact Cranley-Patterson variance of its lattice on a
// fixed family of step edges: for each requested direction, the normals
// direction + {-w, -w/2, 0, w/2, w} (w = window_deg: the served grid's half
// step plus what a direction estimate is off by), each through three
// offsets from the centre; plus the corner term of a non-periodic smooth
// function, (x - 1/2)(y - 1/2), whose coefficients 1/(4 pi^2 a b) sit on the
// hyperbolic cross and keep g away from lattices that are poor in general.
// The score is the mean log variance of the edges plus half the log variance
// of the corner term. Two stages: every candidate on a coarse family (the
// window's ends and middle) over the dual points within 8 sqrt(N), then the
// best `finalists` on the whole family within radius N / 2. Ties go to
// the smallest g, so the choice is a function of (N, directions, options).
class LatticeTermCache;  // core/optimize/lattice_term_cache.h

// The window a tent-folded lattice is chosen for by default: its variance
// swings between neighbouring normals more than a plain lattice's (resonances
// of its two strips), and over +-1 degree its choice lost to Owen-Sobol 2
// degrees off (0.2x at N = 4096, theta = 82); over +-2 degrees, sampled every
// quarter degree, every edge within 2 degrees stayed at least 1.2x below
// (docs/results.md, "Tent-folded lattices").
inline constexpr double kTentLatticeWindowDeg = 2.0;

struct AlignedLatticeOptions {
  double window_deg = 1.0;
  // Choose g for the tent-folded lattice (TentLatticePoints) instead: the
  // variance of f under a shift before the fold is the sum over the dual
  // points of f's cosine coefficients squared,
  //   c(h) = int f(x, y) cos(pi h_x x) cos(pi h_y y),
  // which for a step edge is the spectrum of the edge folded into the four
  // quadrants (directions d and 180 - d; FoldedIndicatorSpectrum). The
  // folded family samples the window at twice as many normals, through six
  // offsets, and scores each direction by the log of its edges' mean
  // variance (the folded variance has narrow resonances a mean of logs
  // would let through); the corner term is x^2 y^2's, whose coefficients
  // 2 (-1)^k / (pi k)^2 (1/3 at k = 0) in each coordinate lie on the
  // hyperbolic cross, as a smooth function's do after the fold, floored at
  // 1e-3 / N^3. Use window_deg = kTentLatticeWindowDeg.
  bool folded = false;
  int finalists = 32;
  int threads = 1;  // 0: all cores; the choice does not depend on it
  // Terms kept between searches (a server's, shared by its workers): a key
  // whose directions were searched before costs milliseconds. The choice
  // does not depend on it.
  LatticeTermCache* cache = nullptr;
};

struct AlignedLatticeChoice {
  uint32_t generator = 0;
  double score = 0.0;           // the final stage's score (lower is better)
  uint32_t candidates = 0;      // generators scored in the first stage
};

// INVALID_ARGUMENT for N outside [16, 2^20], no direction or more than 8, a
// direction that is not finite, or a window outside [0, 10] degrees.
StatusOr<AlignedLatticeChoice> ChooseAlignedLatticeGenerator(
    uint32_t n, const std::vector<double>& directions_deg, const AlignedLatticeOptions& options = {});

// The same for several keys at once, choice for choice what
// ChooseAlignedLatticeGenerator gives each alone (which is this with one
// key): both stages' terms are kept per direction, and each (direction, g)
// is scored once however many keys it serves (a render's two-direction
// pairs share their degrees and often their finalists).
// progress(done, total): total counts the passes (one per direction and
// stage), done how many are done, with fractions of the pass under way
// (about 200 steps a pass); called on the calling thread only.
StatusOr<std::vector<AlignedLatticeChoice>> ChooseAlignedLatticeGenerators(
    uint32_t n, const std::vector<std::vector<double>>& keys, const AlignedLatticeOptions& options = {},
    const std::function<void(double done, double total)>& progress = {});

// The score ChooseAlignedLatticeGenerator's final stage gives generator g
// for these directions (lower is better; the chosen generator's is the
// least). INVALID_ARGUMENT as there, or for g not coprime to N.
StatusOr<double> AlignedLatticeScore(uint32_t n, uint32_t g, const std::vector<double>& directions_deg,
                                     const AlignedLatticeOptions& options = {});

// AlignedLatticeScore for each of several generators of the same N, the
// scored family built once (what a search over extensions of a generator,
// core/optimize/lattice_sequence.h, scores level by level); on
// options.threads threads, each score the same as AlignedLatticeScore's.
StatusOr<std::vector<double>> AlignedLatticeScores(uint32_t n, std::span<const uint32_t> generators,
                                                  const std::vector<double>& directions_deg,
                                                  const AlignedLatticeOptions& options = {});

// The generator of the lattice that a symmetry of the square carries the
// lattice of generator g onto, as a set of points up to a shift: swapping x
// and y (first) takes g to its inverse mod N, inverting x or y (after) to
// N - g; the flags are core/align's AlignOps, which core/optimize does not
// include. The directions map as the symmetry maps them, and so does the
// scored family of edges, so the image of the lattice chosen for a
// canonical key scores for the mapped directions what the choice scored for
// the key: a renderer chooses once per orbit (46 one-direction keys instead
// of 180 degrees). g must be coprime to N.
uint32_t MapLatticeGenerator(uint32_t n, uint32_t g, bool swap, bool invert_x, bool invert_y);

// The lattice with generator g and realization `seed`: the shift is a whole
// number of columns and rows drawn from the seed plus half a cell, so every
// realization is a centred N-rooks set (one point in each column and row, at
// its middle): the midpoint rule in each coordinate.
PointSet Rank1LatticePoints(uint32_t n, uint32_t g, uint64_t seed);
// The same points into `out` (n of them), bit for bit, without allocating.
void Rank1LatticePointsInto(uint32_t n, uint32_t g, uint64_t seed, std::span<Point2> out);

// The tent-folded lattice with generator g and realization `seed`: each
// point of the lattice {frac(i (1, g) / N + s)}, s uniform in [0, 1)^2 drawn
// from the seed, mapped by the tent phi(u) = 1 - |2 u - 1| in each
// coordinate. The fold makes every integrand continuous across the borders
// of the torus the lattice lives on, so a smooth function that is not
// periodic on the square, whose periodic extension jumps at the borders and
// costs a plain lattice its convergence, keeps a fast one (its cosine
// coefficients decay like 1/(h_x h_y)^2); a step edge with normal d becomes
// four half-size edges with normals d and 180 - d, which the generator
// (AlignedLatticeOptions::folded) keeps dark. The shift is continuous, so
// the realizations are unbiased for every integrand (the mean over s is the
// integral: phi maps the uniform measure to itself).
PointSet TentLatticePoints(uint32_t n, uint32_t g, uint64_t seed);

// The continuous shift TentLatticePoints applies for realization `seed`
// before the fold (in [0, 1)^2).
Point2 TentLatticeShift(uint64_t seed);

// TentLatticePoints when `folded`, else Rank1LatticePoints: the points of
// a generator chosen with AlignedLatticeOptions::folded as given.
PointSet LatticePoints(uint32_t n, uint32_t g, uint64_t seed, bool folded);

// The generator g with LatticePoints(N, g, seed, folded) == points, bit
// for bit (N = points.size()); nullopt when the points are no such lattice.
// A cache stores a lattice's points, not its generator: this gives the
// generator back from the points and the realization in O(N), so a server
// can tell a renderer the generator of a set it serves without searching
// again. Candidates come from the first two points and are checked against
// the whole set, so a wrong answer is impossible, only none.
std::optional<uint32_t> LatticeGeneratorOf(const PointSet& points, uint64_t seed, bool folded);

// The tent phi(u) = 1 - |2 u - 1| that folds [0, 1) onto [0, 1]: what
// TentLatticePoints applies after its shift, and a renderer after each
// pixel's shift of the unfolded lattice.
inline double TentFold(double u) { return 1.0 - std::abs(2.0 * u - 1.0); }

// The window a caller that names none uses: 1 degree, kTentLatticeWindowDeg
// folded.
inline double DefaultLatticeWindowDeg(bool folded) {
  return folded ? kTentLatticeWindowDeg : AlignedLatticeOptions{}.window_deg;
}

// ChooseAlignedLatticeGenerator, then Rank1LatticePoints (TentLatticePoints
// with options.folded).
StatusOr<PointSet> AlignedLattice(uint32_t n, const std::vector<double>& directions_deg,
                                  uint64_t seed, const AlignedLatticeOptions& options = {});

}  // namespace alignset

#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "core/util/point_set.h"
#include "core/util/status.h"

namespace alignset {

class LatticeTermCache;  // core/optimize/lattice_term_cache.h

// An aligned lattice sequence: an extensible rank-1 lattice in base 2 whose
// every prefix of 2^m points is an aligned rank-1 lattice of its own, so a
// pixel may stop after any number of samples (adaptive sampling, a
// progressive preview) and still integrate its edge like a lattice of that
// size.
//
// Point i is frac(phi(i) (1, g) + s), phi the base-2 radical inverse over
// kLatticeSequenceLog2 bits and s the realization's shift: for i < 2^m,
// phi(i) runs over k / 2^m, so the first 2^m points are the rank-1 lattice
// {frac(k (1, g mod 2^m) / 2^m + s)}; a prefix between two powers of two is
// that lattice plus part of its half-step coset. The shift is uniform on
// the torus (not the fixed-size lattice's whole cells plus half a cell,
// which no two sizes share), so every prefix, of any length, is unbiased.
//
// How g is chosen: g mod 2^m must be a good generator for 2^m points at
// every m at once, and the candidates for 2^(m+1) points are only g mod 2^m
// and g mod 2^m + 2^m. A prefix's excess at level m is its lattice's score
// (AlignedLatticeScore: the exact variance on the window's step edges and
// the corner term, in logs) less the score of the fixed-size aligned lattice
// of 2^m points (ChooseAlignedLatticeGenerator): the log of how much worse
// than the best fixed-size lattice the prefix is. Every odd g below
// 2^exhaustive_log2 is scored exactly at every level up to there (4095
// scores at 2^12, a second), the `beam` with the least worst excess kept,
// then each extended by one bit a level to 2^16, the beam kept by the same
// rule (then the least sum, then the smallest g), so the choice is a
// function of the directions, the window and the options. Screening every
// g below 2^16 by the fixed-size search's first-stage scores instead was
// measured and chose worse sequences (docs/progressive.md).
inline constexpr int kLatticeSequenceLog2 = 16;
inline constexpr uint32_t kLatticeSequenceMaxPoints = 1u << kLatticeSequenceLog2;
// The prefixes the search weighs: 2^6 = 64 points up to the whole sequence.
// Smaller prefixes follow from g mod 64 and are reported, not weighed.
inline constexpr int kLatticeSequenceFirstWeighedLog2 = 6;

struct LatticeSequenceOptions {
  double window_deg = 1.0;
  int exhaustive_log2 = 12;
  int beam = 64;
  int threads = 1;  // 0: all cores; the choice does not depend on it
  // The fixed-size searches' terms, and a one-direction choice whole (a
  // server asked for one key at several N searches once); the choice does
  // not depend on it.
  LatticeTermCache* cache = nullptr;
};

struct LatticeSequenceLevel {
  uint32_t n = 0;              // 2^m
  double score = 0.0;          // the prefix's AlignedLatticeScore
  double fixed_score = 0.0;    // the fixed-size aligned lattice's
  uint32_t fixed_generator = 0;
  double excess() const { return score - fixed_score; }
};

struct LatticeSequenceChoice {
  uint32_t generator = 0;  // odd, below kLatticeSequenceMaxPoints
  // Levels 4 (16 points) to kLatticeSequenceLog2.
  std::vector<LatticeSequenceLevel> levels;
  double worst_excess = 0.0;  // over the weighed levels
  uint32_t screened = 0;      // generators scored exhaustively (every odd g below 2^exhaustive_log2)
};

// INVALID_ARGUMENT for no direction or more than 8, one that is not finite,
// a window outside [0, 10] degrees, a beam outside [1, 4096] or
// exhaustive_log2 outside [kLatticeSequenceFirstWeighedLog2, 13].
StatusOr<LatticeSequenceChoice> ChooseLatticeSequenceGenerator(const std::vector<double>& directions_deg,
                                                               const LatticeSequenceOptions& options = {});

// The shift of realization `seed`, uniform in [0, 1)^2.
Point2 LatticeSequenceShift(uint64_t seed);

// The first out.size() points (at most kLatticeSequenceMaxPoints) of the
// sequence with generator g and realization `seed`.
void LatticeSequencePointsInto(uint32_t g, uint64_t seed, std::span<Point2> out);
PointSet LatticeSequencePoints(uint32_t n, uint32_t g, uint64_t seed);

}  // namespace alignset

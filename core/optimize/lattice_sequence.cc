#include "core/optimize/lattice_sequence.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <string>
#include <tuple>

#include "core/optimize/aligned_lattice.h"
#include "core/optimize/lattice_term_cache.h"

namespace alignset {
namespace {

constexpr int kLowestLog2 = 4;  // 16 points, the smallest set anything serves

struct Candidate {
  uint32_t g = 0;
  std::vector<double> scores;  // by level, from kLowestLog2
  double worst = -std::numeric_limits<double>::infinity();  // the largest excess over the weighed levels so far
  double sum = 0.0;                                          // their sum
};

bool Better(const Candidate& a, const Candidate& b) {
  return std::tie(a.worst, a.sum, a.g) < std::tie(b.worst, b.sum, b.g);
}

}  // namespace

StatusOr<LatticeSequenceChoice> ChooseLatticeSequenceGenerator(const std::vector<double>& directions_deg,
                                                               const LatticeSequenceOptions& o) {
  if (o.beam < 1 || o.beam > 4096) {
    return Status::InvalidArgument("lattice sequence: beam must be in [1, 4096], got " + std::to_string(o.beam));
  }
  if (o.exhaustive_log2 < kLatticeSequenceFirstWeighedLog2 || o.exhaustive_log2 > 13) {
    return Status::InvalidArgument("lattice sequence: exhaustive_log2 must be in [" +
                                   std::to_string(kLatticeSequenceFirstWeighedLog2) + ", 13], got " +
                                   std::to_string(o.exhaustive_log2));
  }
  // A one-direction choice under the default search is kept whole in the
  // caller's cache: the key's sets at every N read one sequence.
  const bool keep = o.cache != nullptr && directions_deg.size() == 1 && o.beam == LatticeSequenceOptions{}.beam &&
                    o.exhaustive_log2 == LatticeSequenceOptions{}.exhaustive_log2 && std::isfinite(directions_deg[0]);
  const LatticeTermCache::Key kept{0, LatticeTermCache::Stage::kSequence, o.window_deg,
                                   keep ? directions_deg[0] : 0.0, false};
  if (keep) {
    if (auto held = std::static_pointer_cast<const LatticeSequenceChoice>(o.cache->FindObject(kept))) return *held;
  }
  AlignedLatticeOptions lattice;
  lattice.window_deg = o.window_deg;
  lattice.threads = o.threads;
  lattice.cache = o.cache;
  LatticeSequenceChoice choice;
  // The fixed-size aligned lattices every level is measured against (their
  // searches validate the directions and the window).
  for (int m = kLowestLog2; m <= kLatticeSequenceLog2; ++m) {
    auto fixed = ChooseAlignedLatticeGenerator(1u << m, directions_deg, lattice);
    if (!fixed.ok()) return Status::InvalidArgument("lattice sequence: " + fixed.status().message());
    LatticeSequenceLevel& level = choice.levels.emplace_back();
    level.n = 1u << m;
    level.fixed_score = fixed->score;
    level.fixed_generator = fixed->generator;
  }
  const auto fixed_score = [&](int m) { return choice.levels[static_cast<size_t>(m - kLowestLog2)].fixed_score; };
  // Scores every candidate at level m (each distinct g mod 2^m once) and
  // adds the level to its worst and sum when the level is weighed.
  const auto score_level = [&](int m, std::vector<Candidate>& candidates) -> Status {
    const uint32_t mask = (1u << m) - 1;
    std::vector<uint32_t> residues;
    for (const Candidate& c : candidates) residues.push_back(c.g & mask);
    std::sort(residues.begin(), residues.end());
    residues.erase(std::unique(residues.begin(), residues.end()), residues.end());
    auto scores = AlignedLatticeScores(1u << m, residues, directions_deg, lattice);
    if (!scores.ok()) return scores.status();
    for (Candidate& c : candidates) {
      const size_t at =
          static_cast<size_t>(std::lower_bound(residues.begin(), residues.end(), c.g & mask) - residues.begin());
      c.scores.push_back((*scores)[at]);
      if (m >= kLatticeSequenceFirstWeighedLog2) {
        const double excess = (*scores)[at] - fixed_score(m);
        c.worst = std::max(c.worst, excess);
        c.sum += excess;
      }
    }
    return Status::Ok();
  };
  const auto prune = [&](std::vector<Candidate>& candidates) {
    const size_t keep = std::min(candidates.size(), static_cast<size_t>(o.beam));
    std::partial_sort(candidates.begin(), candidates.begin() + static_cast<std::ptrdiff_t>(keep), candidates.end(),
                      Better);
    candidates.resize(keep);
  };
  std::vector<Candidate> beam;
  for (uint32_t g = 1; g < (1u << o.exhaustive_log2); g += 2) {
    Candidate c;
    c.g = g;
    beam.push_back(std::move(c));
  }
  for (int m = kLowestLog2; m <= o.exhaustive_log2; ++m) {
    if (Status s = score_level(m, beam); !s.ok()) return s;
  }
  prune(beam);
  for (int m = o.exhaustive_log2 + 1; m <= kLatticeSequenceLog2; ++m) {
    std::vector<Candidate> children;
    children.reserve(2 * beam.size());
    for (const Candidate& c : beam) {
      children.push_back(c);
      Candidate high = c;
      high.g += 1u << (m - 1);
      children.push_back(std::move(high));
    }
    if (Status s = score_level(m, children); !s.ok()) return s;
    prune(children);
    beam = std::move(children);
  }
  const Candidate& best = beam.front();
  choice.generator = best.g;
  choice.worst_excess = best.worst;
  choice.screened = 1u << (o.exhaustive_log2 - 1);
  for (size_t i = 0; i < choice.levels.size(); ++i) choice.levels[i].score = best.scores[i];
  if (keep) {
    o.cache->PutObject(kept, std::make_shared<const LatticeSequenceChoice>(choice),
                       sizeof(LatticeSequenceChoice) + choice.levels.size() * sizeof(LatticeSequenceLevel));
  }
  return choice;
}

}  // namespace alignset

#include <cstdio>

#include "core/optimize/aligned_lattice.h"
#include "core/optimize/aligned_net.h"
#include "core/optimize/construction.h"
#include "core/optimize/lattice_sequence.h"

// Building a construction's set: apart from the table of constructions
// (construction.cc), which a renderer's sampler links without the searches.
namespace alignset {

StatusOr<ConstructedSet> Construction::Build(uint32_t n, const std::vector<double>& directions_deg,
                                             uint64_t seed, const ConstructionContext& context) const {
  ConstructedSet out;
  char detail[192];
  if (lattice()) {
    AlignedLatticeOptions options;
    options.folded = folded();
    options.window_deg = window_deg;
    options.threads = context.threads;
    options.cache = context.lattice_terms;
    auto choice = ChooseAlignedLatticeGenerator(n, directions_deg, options);
    if (!choice.ok()) return choice.status();
    out.points = LatticePoints(n, choice->generator, seed, folded());
    out.lattice_generator = choice->generator;
    std::snprintf(detail, sizeof(detail), "generator=%u score=%.6g candidates=%u", choice->generator,
                  choice->score, choice->candidates);
    out.detail = detail;
    return out;
  }
  if (kind == ConstructionKind::kNet) {
    AlignedNetOptions options;
    options.window_deg = window_deg;
    auto net = AlignedNet(n, directions_deg, seed, options);
    if (!net.ok()) return net.status();
    out.points = std::move(net->points);
    out.iterations = net->sweeps;
    std::snprintf(detail, sizeof(detail), "objective %.4g -> %.4g flips=%d sweeps=%d", net->start_objective,
                  net->objective, net->flips, net->sweeps);
    out.detail = detail;
    return out;
  }
  if (kind == ConstructionKind::kLatticeSequence) {
    if (Status s = ValidateSize(n); !s.ok()) return s;
    LatticeSequenceOptions options;
    options.window_deg = window_deg;
    options.threads = context.threads;
    options.cache = context.lattice_terms;
    auto choice = ChooseLatticeSequenceGenerator(directions_deg, options);
    if (!choice.ok()) return choice.status();
    out.points = LatticeSequencePoints(n, choice->generator, seed);
    out.lattice_generator = choice->generator;
    std::snprintf(detail, sizeof(detail), "sequence generator=%u worst prefix excess=%.3g (log of the ratio to "
                  "the fixed-size lattice)", choice->generator, choice->worst_excess);
    out.detail = detail;
    return out;
  }
  return Status::FailedPrecondition("the optimized sets are not constructed: run the optimizer");
}

}  // namespace alignset

#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <alignset/set_choice.h>

#include "render/aligned_sets.h"
#include "render/direction.h"
#include "core/util/status.h"

namespace alignset::render {

// The aligned rank-1 lattices a render reads (sampler aligned-lattice): for
// every served degree and pair the direction maps choose under `policy`, the
// lattice whose generator core/optimize/aligned_lattice.h chooses for that
// direction (window `window_deg`). Built locally, no server: a generator
// takes milliseconds (13 ms at N = 1024, 80 ms at 4096), chosen once per
// canonical key (core/align/canonical.h), all keys in one batch that
// shares each degree's work between the pairs it is in, and mapped onto
// the degree or pair by the square's symmetries (MapLatticeGenerator), as
// the service serves its lattices; the same key always gives the same
// lattice. The sets are a table of the sampler library (partial sections
// of the keys searched, construction "lattice" or "tent-lattice"), as the
// fetched sets are, so the aligned sampler reads either.
struct LatticeTableStats {
  size_t one = 0, two = 0;  // served degrees and pairs in the table
  size_t searched = 0;      // generator searches: one per canonical key (and size)
  size_t smaller = 0;       // canonical keys given fewer than N points (size_span)
  double mean_points = 0.0; // points per canonical key, on average
  double seconds = 0.0;
};
//
// folded (sampler aligned-tent-lattice): the generators are chosen for the
// tent-folded lattice (AlignedLatticeOptions::folded) and the table's
// construction is "tent-lattice": a pixel's shift goes before the fold.
//
// size_span > 0: each key's lattice may have N' in [N - size_span, N] points
// instead of N, the size whose chosen generator scores best (the score is
// the exact variance of the window's edges with N' points, so fewer points
// win only where their lattice lies better along the key's directions; ties
// go to the larger; the table keeps each key's size). A pixel then spends
// at most N samples. The search
// costs size_span + 1 times as much. INVALID_ARGUMENT for a span that
// leaves N' below 16.
// OK for a size span AlignedLatticeTable takes at N (0 always; else
// N - size_span at least 16), INVALID_ARGUMENT otherwise: a caller can refuse
// a bad span before any work.
Status CheckLatticeSizeSpan(uint32_t n, uint32_t size_span);

StatusOr<RenderSets> AlignedLatticeTable(
    uint32_t n, const std::vector<const std::vector<PixelDirection>*>& direction_maps,
    const AlignedPolicy& policy, double window_deg, int threads, LatticeTableStats* stats = nullptr,
    const std::function<void(double done, double total)>& progress = {}, bool folded = false,
    uint32_t size_span = 0);

}  // namespace alignset::render

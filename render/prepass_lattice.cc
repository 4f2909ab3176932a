#include "render/prepass_lattice.h"

#include <alignset/prepass_fit.h>

namespace alignset::render {

// The sampler library's (sampler/prepass_fit.cc): one home for the pre-pass.
PointSet PrepassLatticePoints(uint32_t m, uint64_t seed) {
  PointSet points(m);
  PrepassLatticePointsInto(seed, points);
  return points;
}

}  // namespace alignset::render

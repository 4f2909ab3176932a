#include "render/prepass_lattice.h"

#include "render/pixel_samplers.h"
#include "core/sampling/rank1_lattice.h"
#include "core/util/hash.h"

namespace alignset::render {

namespace {

// The salt of the pre-pass lattice's shift: not a sampler's salt, so the
// pre-pass is independent of every sampler's own randomization.
constexpr uint64_t kSaltPrepassLattice = 0x6c61747469636501ull;

double Wrap(double u) { return u >= 1.0 ? u - 1.0 : u; }

}  // namespace

PointSet PrepassLatticePoints(uint32_t m, uint64_t seed) {
  const uint64_t g = Rank1Generator(m);
  const Point2 s = HashShift(HashCombine(seed, kSaltPrepassLattice));
  PointSet points(m);
  for (uint64_t j = 0; j < m; ++j) {
    points[j] = {Wrap(static_cast<double>(j) / m + s.x), Wrap(static_cast<double>((j * g) % m) / m + s.y)};
  }
  return points;
}

}  // namespace alignset::render

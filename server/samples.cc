#include "server/samples.h"

#include "core/sampling/samplers.h"
#include "core/sampling/shear.h"

namespace alignset::server {

std::vector<std::string> BaselineSamplerNames() { return SamplerNames(); }

StatusOr<PointSet> MakeBaselineSamples(const std::string& sampler, uint32_t n, uint64_t seed,
                                       std::optional<double> shear_deg) {
  // The registry validates the name (listing the known ones) and N.
  auto points = Sample(sampler, n, seed);
  if (!points.ok()) return points.status();
  if (shear_deg) return Shear(*points, *shear_deg);
  return points;
}

}  // namespace alignset::server

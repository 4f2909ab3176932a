#include "server/samples.h"

#include <algorithm>

#include "core/sampling/samplers.h"
#include "core/sampling/shear.h"
#include "server/log_text.h"

namespace alignset::server {

std::vector<std::string> BaselineSamplerNames() { return SamplerNames(); }

StatusOr<PointSet> MakeBaselineSamples(const std::string& sampler, uint32_t n, uint64_t seed,
                                       std::optional<double> shear_deg) {
  // The name is checked here rather than by the registry, whose message
  // echoes the name whole: a client's string goes into messages and logs
  // only quoted and cut (server/log_text.h).
  const std::vector<std::string> names = SamplerNames();
  if (std::find(names.begin(), names.end(), sampler) == names.end()) {
    std::string known;
    for (const std::string& k : names) known += (known.empty() ? "" : ", ") + k;
    return Status::InvalidArgument("unknown sampler " + Quoted(sampler) + " (known: " + known + ")");
  }
  auto points = Sample(sampler, n, seed);
  if (!points.ok()) return points.status();
  if (shear_deg) return Shear(*points, *shear_deg);
  return points;
}

}  // namespace alignset::server

#include "server/samples.h"

#include "core/owen_sobol.h"

namespace alignset::server {

// Until the core's sampler registry lands, only the optimizer's own start.
std::vector<std::string> BaselineSamplerNames() { return {"owen_sobol"}; }

StatusOr<PointSet> MakeBaselineSamples(const std::string& sampler, uint32_t n, uint64_t seed,
                                       std::optional<double> shear_deg) {
  if (sampler != "owen_sobol") {
    return Status::InvalidArgument("unknown sampler '" + sampler + "' (known: owen_sobol)");
  }
  if (shear_deg) return Status::InvalidArgument("shearing is not available yet");
  return OwenScrambledSobol(n, seed);
}

}  // namespace alignset::server

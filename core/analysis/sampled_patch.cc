#include <cmath>
#include <string>

#include "core/analysis/patch_spectrum.h"

// A scattered patch's checks, apart from the spectra (patch_spectrum.cc):
// the edge-line fit and a renderer's sampler need them without an FFT.
namespace alignset {

Status ValidateSampledPatch(const SampledPatch& patch) {
  if (patch.points.empty()) return Status::InvalidArgument("no samples given");
  if (static_cast<int64_t>(patch.points.size()) > kMaxPatchSamples) {
    return Status::InvalidArgument("at most " + std::to_string(kMaxPatchSamples) +
                                   " samples, got " + std::to_string(patch.points.size()));
  }
  if (patch.values.size() != patch.points.size()) {
    return Status::InvalidArgument(std::to_string(patch.points.size()) + " sample positions but " +
                                   std::to_string(patch.values.size()) + " values");
  }
  for (size_t j = 0; j < patch.points.size(); ++j) {
    const Point2& p = patch.points[j];
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(patch.values[j])) {
      return Status::InvalidArgument("sample " + std::to_string(j) + " is not finite");
    }
    if (p.x < 0.0 || p.x > 1.0 || p.y < 0.0 || p.y > 1.0) {
      return Status::InvalidArgument("sample " + std::to_string(j) + " at (" + std::to_string(p.x) +
                                     ", " + std::to_string(p.y) + ") is outside [0,1]^2");
    }
  }
  return Status::Ok();
}

}  // namespace alignset

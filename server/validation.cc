#include "server/validation.h"

#include <cmath>
#include <cstdio>
#include <string>

#include "core/optimize/optimizer.h"
#include "core/optimize/point_count.h"
#include "core/optimize/realization.h"

namespace alignset::server {

Status ValidatePointCount(uint32_t n, uint32_t max_n) {
  if (Status s = ::alignset::ValidatePointCount(n); !s.ok()) return s;
  if (n > max_n) {
    return Status::InvalidArgument("N = " + std::to_string(n) + " is above this server's maximum of " +
                                   std::to_string(max_n) + " points (--max-n)");
  }
  return Status::Ok();
}

StatusOr<Canonicalization> ValidateAlignedSetRequest(uint32_t n,
                                                     const std::vector<double>& directions_deg,
                                                     uint32_t max_n) {
  return ValidateAlignedSetRequest(n, directions_deg, max_n, AngleGrid::kWholeDegree);
}

StatusOr<AngleGrid> ResolveAngleGrid(uint32_t steps_per_degree, AngleGrid fallback) {
  if (steps_per_degree == 0) return fallback;
  if (steps_per_degree == 1) return AngleGrid::kWholeDegree;
  if (steps_per_degree == 4) return AngleGrid::kQuarterDegree;
  return Status::InvalidArgument("steps_per_degree must be 0 (server default), 1 or 4, got " +
                                 std::to_string(steps_per_degree));
}

StatusOr<Canonicalization> ValidateAlignedSetRequest(uint32_t n,
                                                     const std::vector<double>& directions_deg,
                                                     uint32_t max_n, AngleGrid grid) {
  if (Status s = ValidatePointCount(n, max_n); !s.ok()) return s;
  if (directions_deg.empty() || directions_deg.size() > 2) {
    // The service's canonical spaces are one and two directions (46 and 4141
    // keys). Sets for 3 to 8 arbitrary directions are not cached: they have
    // no small canonical space to precompute (three whole-degree directions
    // alone make about 2.5e5 orbits under the same group), so they are
    // refused here and made locally (docs/results.md, "Any number of directions").
    std::string hint;
    if (directions_deg.size() > 2) {
      hint = "; sets for up to 8 directions are made locally: alignset optimize --dir A --dir B "
             "--dir C ...";
    }
    return Status::InvalidArgument(
        "give one or two directions (degrees; 0 and 90 are always included), got " +
        std::to_string(directions_deg.size()) + hint);
  }
  for (size_t i = 0; i < directions_deg.size(); ++i) {
    if (!std::isfinite(directions_deg[i])) {
      return Status::InvalidArgument("direction " + std::to_string(i) + " is not a finite number");
    }
    // Beyond this, doubles no longer resolve whole degrees.
    if (std::fabs(directions_deg[i]) > 1e15) {
      char text[64];
      std::snprintf(text, sizeof text, "%g", directions_deg[i]);
      return Status::InvalidArgument("direction " + std::to_string(i) + " = " + text +
                                     " degrees is too large (at most 1e15 in magnitude)");
    }
  }
  return Canonicalize(directions_deg, grid);
}

}  // namespace alignset::server

namespace alignset::server {

Status ValidateBatchSize(size_t items, uint64_t total_points) {
  if (items == 0) return Status::InvalidArgument("the batch has no items");
  if (items > kMaxBatchItems) {
    return Status::InvalidArgument("the batch has " + std::to_string(items) + " items, above the " +
                                   "maximum of " + std::to_string(kMaxBatchItems) +
                                   " per call: split it");
  }
  if (total_points > kMaxBatchPoints) {
    return Status::InvalidArgument("the batch asks for " + std::to_string(total_points) +
                                   " points in all, above the maximum of " +
                                   std::to_string(kMaxBatchPoints) + " per call: split it");
  }
  return Status::Ok();
}

}  // namespace alignset::server

namespace alignset::server {

Status ValidateRealization(uint32_t realization) {
  if (realization > kMaxRealization) {
    return Status::InvalidArgument("realization " + std::to_string(realization) +
                                   " is above the maximum of " + std::to_string(kMaxRealization));
  }
  return Status::Ok();
}

Status ValidateRealizationCount(uint32_t count) {
  if (count > kMaxRealization + 1) {
    return Status::InvalidArgument("realizations = " + std::to_string(count) +
                                   " is above the maximum of " + std::to_string(kMaxRealization + 1));
  }
  return Status::Ok();
}

}  // namespace alignset::server

#include "core/optimize/point_count.h"

#include <string>

#include "core/optimize/construction.h"
#include "core/optimize/optimizer.h"

namespace alignset {

Status ValidatePointCount(uint32_t n) {
  if (n < kMinPoints) {
    // 0 is what a request that left N out carries.
    return Status::InvalidArgument("N = " + std::to_string(n) + " is below the minimum of " +
                                   std::to_string(kMinPoints) + " points" + (n == 0 ? " (missing?)" : ""));
  }
  if (n > kMaxPoints) {
    return Status::InvalidArgument("N = " + std::to_string(n) + " is above the maximum of " +
                                   std::to_string(kMaxPoints) + " points");
  }
  return Status::Ok();
}

Status ValidatePointCount(uint32_t n, const Construction& construction) {
  if (Status s = ValidatePointCount(n); !s.ok()) return s;
  return construction.ValidateSize(n);
}

}  // namespace alignset

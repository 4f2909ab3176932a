#include "core/spectral/fftw_planner_lock.h"

namespace alignset {

std::mutex& FftwPlannerLock() {
  static std::mutex mu;
  return mu;
}

}  // namespace alignset

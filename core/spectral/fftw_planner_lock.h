#pragma once

#include <mutex>

namespace alignset {

// FFTW's planner keeps global state: every plan anywhere in the process
// (the NUFFT grids, the direction estimator's patch transforms) is made and
// destroyed under this one lock, so that work in different threads can set
// up transforms at once. fftw_execute needs no lock.
std::mutex& FftwPlannerLock();

}  // namespace alignset

#pragma once

#include <memory>
#include <string>

#include "core/spectral/spectral_engine.h"
#include "core/util/status.h"

namespace alignset {

// The CUDA engine (built only when nvcc is found; ALIGNSET_HAVE_CUDA is then
// defined for everything that links alignset_core).
//
// Exact sums on the GPU, like the direct engine, so that it is correct by
// construction: positions are converted to 64-bit fixed point, the phase of
// v.s is formed modulo 1 in integer arithmetic (a * x + b * y wraps exactly
// modulo 2^64), and only the final fraction of a turn goes through sincospi
// in double precision. Every term is therefore accurate to a few ulps for
// any |v|, and sums are accumulated in double in a fixed order (results are
// deterministic). Cost O(N |K|) per pass, spread over the whole device.
//
// Returns Unavailable, with the reason, when no CUDA device can be used
// (no driver, no device, or the device count query fails).
StatusOr<std::unique_ptr<SpectralEngine>> MakeCudaEngine(int threads);

// Whether a CUDA device is usable here; `why` says why not.
bool CudaDeviceAvailable(std::string* why);

}  // namespace alignset

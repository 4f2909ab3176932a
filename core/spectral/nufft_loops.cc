#include "core/spectral/nufft_loops.h"

namespace alignset {

// Defined in core/nufft_loops_generic.cc and core/nufft_loops_avx2.cc.
const NufftLoops& NufftLoopsGeneric();
const NufftLoops& NufftLoopsAvx2();

const NufftLoops& GenericNufftLoops() { return NufftLoopsGeneric(); }

const NufftLoops& SelectedNufftLoops() {
  static const NufftLoops& loops = [] () -> const NufftLoops& {
#if defined(ALIGNSET_NUFFT_AVX2) && (defined(__x86_64__) || defined(__i386__))
    __builtin_cpu_init();
    if (__builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma")) return NufftLoopsAvx2();
#endif
    return NufftLoopsGeneric();
  }();
  return loops;
}

}  // namespace alignset

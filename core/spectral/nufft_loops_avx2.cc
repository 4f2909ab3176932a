// The NUFFT loops for x86-64 CPUs with AVX2 and FMA (compiled with -mavx2
// -mfma by core/CMakeLists.txt; elsewhere this is a second generic copy).
#define ALIGNSET_NUFFT_ISA NufftLoopsAvx2
#define ALIGNSET_NUFFT_ISA_NAME "avx2+fma"
#include "core/spectral/nufft_loops_impl.h"

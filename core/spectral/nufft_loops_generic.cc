// The NUFFT loops for any CPU (the baseline instruction set of the build).
#define ALIGNSET_NUFFT_ISA NufftLoopsGeneric
#define ALIGNSET_NUFFT_ISA_NAME "generic"
#include "core/spectral/nufft_loops_impl.h"

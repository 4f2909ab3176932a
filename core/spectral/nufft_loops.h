#pragma once

#include <complex>
#include <cstddef>

namespace alignset {

// The three inner loops of the NUFFT, compiled once per instruction set
// (core/nufft_loops_generic.cc, and core/nufft_loops_avx2.cc with AVX2 and
// FMA on x86-64) and picked at run time for the CPU at hand. Each loop is
// instantiated for every kernel width, so the taps are unrolled.
struct NufftLoops {
  // For each of `count` coordinates x (grid units, on a grid of n points):
  // the width kernel values into k[i * width ...] (tap polynomials of
  // `degree` with coefficients[d * width + t], see EsKernel) and the first
  // grid index, wrapped into [0, n), into first[i].
  void (*weights)(const double* coefficients, int degree, int width, const double* x,
                  size_t count, int n, double* k, int* first);
  // Adds the tensor-product kernel of each point (unit strength) to a real
  // grid with rows of `stride` doubles; the grid is padded (width - 1 extra
  // rows and columns) so that nothing wraps here.
  void (*spread)(double* grid, size_t stride, int width, const double* k1, const double* k2,
                 const int* row, const int* col, size_t count);
  // The reverse on a padded complex grid: out[i] = the sum of the grid
  // under point i's kernel.
  void (*interpolate)(const std::complex<double>* grid, size_t stride, int width,
                      const double* k1, const double* k2, const int* row, const int* col,
                      size_t count, std::complex<double>* out);
  const char* isa;
};

// The fastest variant this CPU runs (chosen once).
const NufftLoops& SelectedNufftLoops();
// The portable variant (for tests comparing the two).
const NufftLoops& GenericNufftLoops();

}  // namespace alignset

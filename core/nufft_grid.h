#pragma once

#include <complex>
#include <cstdint>
#include <vector>

#include "core/lattice_basis.h"
#include "core/nufft_kernel.h"
#include "core/point_set.h"
#include "core/thread_pool.h"

namespace alignset {

// The smallest n >= min_size whose prime factors are 2, 3, 5 and 7 (sizes
// FFTW transforms fastest).
int FastFftSize(int min_size);

// Grid size along one axis for modes |w| <= m at the kernel's oversampling.
int NufftGridSize(int64_t m, const EsKernel& kernel);

// One NUFFT grid: the modes |w1| <= m1, |w2| <= m2 of the points mapped
// into a lattice basis, u = (p.s, q.s) mod 1.
//
//   type 1:  Mode(w) = sum_j exp(-2 pi i w.u_j)                (unit strengths)
//   type 2:  out_j  += sum_w c(w) exp(-2 pi i w.u_j)
//
// Spreading is deterministic and free of races without per-thread grids:
// points are sorted (stably) into slabs of grid rows at least one kernel
// width tall, and even slabs, then odd ones, are spread in parallel, so no
// two slabs running at once touch the same row and each cell adds its
// contributions in a fixed order whatever the thread count.
//
// Not thread-safe: one grid belongs to one engine. FFTW plans are made once
// here (under a process-wide lock, since FFTW's planner is not reentrant)
// and reused by every evaluation.
class NufftGrid {
 public:
  NufftGrid(const BasisBox& box, const EsKernel& kernel);
  ~NufftGrid();
  NufftGrid(const NufftGrid&) = delete;
  NufftGrid& operator=(const NufftGrid&) = delete;

  int n1() const { return n1_; }
  int n2() const { return n2_; }
  const BasisBox& box() const { return box_; }

  // Maps and sorts the points, and computes their kernel weights once for
  // both passes when keep_weights (memory: 2 * width doubles per point).
  void Prepare(const PointSet& points, bool keep_weights, ThreadPool& pool);

  // Type 1: spreads unit strengths and transforms; then Mode() answers.
  void Spread(ThreadPool& pool);
  void TransformSpread();
  std::complex<double> Mode(int64_t w1, int64_t w2) const;

  // Type 2: coefficients are added mode by mode (a mode added twice sums).
  void ClearCoefficients();
  void AddCoefficient(int64_t w1, int64_t w2, std::complex<double> c);
  void TransformCoefficients();
  void Interpolate(ThreadPool& pool, std::complex<double>* out) const;

 private:
  // Kernel weights and first row/column of the point at sorted position pos.
  template <int W>
  void WeightsAt(size_t pos, double* k1, double* k2, int* row, int* col) const;
  template <int W>
  void SpreadSlabs(ThreadPool& pool);
  template <int W>
  void InterpolatePoints(ThreadPool& pool, std::complex<double>* out) const;

  BasisBox box_;
  const EsKernel& kernel_;
  int width_;
  int n1_, n2_;
  int stride_;  // row length of the padded grids: n2 + width - 1
  int slabs_;
  std::vector<double> inv_phi_hat1_, inv_phi_hat2_;

  // Points in slab order.
  size_t count_ = 0;
  std::vector<uint32_t> order_;          // sorted position -> point index
  std::vector<size_t> slab_start_;       // first sorted position of each slab
  std::vector<double> x1_, x2_;          // grid coordinates, sorted
  bool weights_kept_ = false;
  std::vector<double> k1_, k2_;          // width per point, when kept
  std::vector<int> row_, col_;
  std::vector<uint16_t> slab_of_;        // scratch for the sort
  std::vector<double> scratch1_, scratch2_;

  std::vector<double> spread_;                 // padded real grid
  std::vector<std::complex<double>> gather_;   // padded complex grid
  double* fft_real_ = nullptr;                 // n1 x n2
  std::complex<double>* fft_half_ = nullptr;   // n1 x (n2 / 2 + 1)
  std::complex<double>* fft_full_ = nullptr;   // n1 x n2
  void* plan_r2c_ = nullptr;
  void* plan_c2c_ = nullptr;
};

}  // namespace alignset

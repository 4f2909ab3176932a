#pragma once

#include <complex>
#include <cstdint>
#include <vector>

#include "core/spectral/lattice_basis.h"
#include "core/spectral/nufft_kernel.h"
#include "core/spectral/nufft_loops.h"
#include "core/util/point_set.h"

namespace alignset {

// The smallest n >= min_size whose prime factors are 2, 3, 5 and 7 (sizes
// FFTW transforms fastest).
int FastFftSize(int min_size);

// Grid size along one axis for modes |w| <= m at the kernel's oversampling.
int NufftGridSize(int64_t m, const EsKernel& kernel);

// One NUFFT grid: the modes |w1| <= m1, |w2| <= m2 of the points mapped
// into a lattice basis, u = (p.s, q.s) mod 1.
//
//   type 1:  Mode(w) = sum_j f_j exp(-2 pi i w.u_j)   (real strengths f_j,
//                                                       1 unless SetStrengths)
//   type 2:  sum_w c(w) exp(-2 pi i w.u_j)   for every point j
//
// The grid does no threading itself: its work comes in stages over ranges
// (of points, sorted positions or slabs) that the engine runs in parallel
// across all its grids at once, with as few synchronizations as possible.
// Spreading is deterministic and free of races without per-thread grids:
// points are sorted (stably) into slabs of grid rows at least one kernel
// width tall, and even slabs, then odd ones, are spread, so no two slabs of
// one pass touch the same row and each cell adds its contributions in a
// fixed order whatever the thread count. (The last slab spills into padding
// rows below the grid, folded back at the end, so nothing wraps.)
//
// FFTW plans are made once here (under a process-wide lock, since FFTW's
// planner is not reentrant) and reused by every evaluation.
class NufftGrid {
 public:
  // Scratch for the kernel weights of a block of points, one per worker,
  // used when the weights are not kept between the passes.
  struct Scratch {
    std::vector<double> k1, k2;
    std::vector<int> row, col;
  };
  static constexpr size_t kScratchBlock = 256;

  NufftGrid(const BasisBox& box, const EsKernel& kernel);
  ~NufftGrid();
  NufftGrid(const NufftGrid&) = delete;
  NufftGrid& operator=(const NufftGrid&) = delete;

  int n1() const { return n1_; }
  int n2() const { return n2_; }
  int slabs() const { return slabs_; }
  const BasisBox& box() const { return box_; }

  // Stage 1: sizes the per-point arrays (serial) ...
  void Resize(size_t count, bool keep_weights);
  // Real strengths of the next type-1 pass, by point index (nullptr: all
  // 1). Kept weights then carry the strengths, so a type-2 pass must not
  // follow a weighted type-1 pass without a new Resize / ComputeWeights.
  void SetStrengths(const double* by_point) { strengths_ = by_point; }
  // ... and maps points [begin, end) (any ranges, in parallel).
  void MapPoints(const PointSet& points, size_t begin, size_t end);
  // Stage 2 (one call per grid): stable counting sort into slabs; clears
  // the spreading grid.
  void SortIntoSlabs();
  size_t SlabBegin(int slab) const { return slab_start_[slab]; }
  size_t SlabEnd(int slab) const { return slab_start_[slab + 1]; }
  // Stage 3, when keeping weights: sorted positions [begin, end).
  void ComputeWeights(size_t begin, size_t end);
  // Stage 4: spreads sorted positions [begin, end) lying in slabs of one
  // parity (all calls of one parity may run at once).
  void SpreadRange(size_t begin, size_t end, Scratch* scratch);
  // The modes this grid serves, w_i = (w1[i], w2[i]) inside the box: the
  // cells and deconvolution factors of each are found once here, not on
  // every evaluation.
  void BindModes(const std::vector<int32_t>& w1, const std::vector<int32_t>& w2);
  // Stage 5 (one call per grid): folds the padding and transforms.
  void FinishSpread();
  // The type-1 sum at bound mode i.
  std::complex<double> Mode(size_t i) const {
    const std::complex<double> v = fft_half_[mode_cell_[i]];
    return corr_[i] * (mode_conj_[i] ? std::conj(v) : v);
  }

  // Type 2, one grid per thread: the coefficients c(w_i) and c(-w_i) of
  // the bound modes (a cell added twice sums), then the transform.
  void ClearCoefficients();
  void AddCoefficients(size_t i, std::complex<double> at_plus, std::complex<double> at_minus) {
    coef_[coef_plus_[i]] += corr_[i] * at_plus;
    coef_[coef_minus_[i]] += corr_[i] * at_minus;
  }
  void FinishCoefficients();
  // by_point[j] = the type-2 sum at point j, for the points at sorted
  // positions [begin, end) (ranges may run at once).
  void InterpolateRange(size_t begin, size_t end, std::complex<double>* by_point,
                        Scratch* scratch) const;

 private:
  // Weights of sorted positions [begin, end) into scratch (at most
  // kScratchBlock).
  void BlockWeights(size_t begin, size_t end, Scratch* scratch) const;
  // Scales the first-axis weights k1[(pos - begin) * width ...] of sorted
  // positions [begin, end) by their points' strengths.
  void ApplyStrengths(size_t begin, size_t end, double* k1) const;

  BasisBox box_;
  const EsKernel& kernel_;
  const NufftLoops& loops_;
  int width_;
  int n1_, n2_;
  int stride_;  // row length of the padded grids: n2 + width - 1
  int slabs_;
  std::vector<double> inv_phi_hat1_, inv_phi_hat2_;

  size_t count_ = 0;
  bool keep_weights_ = false;
  const double* strengths_ = nullptr;
  // Per point, in input order.
  std::vector<double> mapped1_, mapped2_;
  std::vector<uint16_t> slab_of_;
  // Per sorted position.
  std::vector<size_t> slab_start_;
  std::vector<uint32_t> order_;  // sorted position -> point index
  std::vector<double> x1_, x2_;  // grid coordinates
  std::vector<double> k1_, k2_;  // width weights per point, when kept
  std::vector<int> row_, col_;

  // Padded grids: n1 + width - 1 rows of stride cells.
  std::vector<double> spread_;                 // real, for type 1
  std::vector<std::complex<double>> gather_;   // complex, for type 2
  std::complex<double>* fft_half_ = nullptr;   // n1 x (n2 / 2 + 1), type 1's modes
  // Type 2's coefficients, n1 x (2 m2 + 1) (column w2 + m2), zero but at
  // the bound modes' cells, and the grid after the column pass, n1 x n2
  // (zero outside the box's columns).
  int m2_ = 0;
  int coef_width_ = 1;
  std::complex<double>* coef_ = nullptr;
  // Per bound mode: 1 / (phi_hat(w1) phi_hat(w2)), its cell in the half
  // spectrum (and whether that cell holds -w), its cells of +-w in coef_.
  std::vector<double> corr_;
  std::vector<size_t> mode_cell_;
  std::vector<uint8_t> mode_conj_;
  std::vector<size_t> coef_plus_, coef_minus_;
  std::complex<double>* mid_ = nullptr;
  void* plan_rows_r2c_ = nullptr;
  void* plan_cols_half_ = nullptr;
  void* plan_cols_pos_ = nullptr;
  void* plan_cols_neg_ = nullptr;
  void* plan_rows_c2c_ = nullptr;
};

}  // namespace alignset

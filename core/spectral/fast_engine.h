#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

#include "core/spectral/nufft_grid.h"
#include "core/spectral/nufft_kernel.h"
#include "core/spectral/spectral_engine.h"
#include "core/util/thread_pool.h"

namespace alignset {

// The fast CPU engine: F over K by type-1 NUFFTs and the gradient by one
// complex type-2 NUFFT, on FFTW.
//
// K is sparse (a disk and thin strips through the origin), so it is split
// into pieces (PartitionFrequencies), each evaluated on its own small grid:
// the disk on its bounding box, each strip on a thin box in a lattice basis
// that follows the strip (an integer unimodular change of coordinates, which
// maps the points by a torus bijection). Per pass the cost is
// O(N w^2 per piece + grid FFTs) instead of O(N |K|).
//
// Both halves of +-v are put on the grids: the spread strengths are real, so
// type 1 needs only a real-to-complex FFT, and the two gradient components
// come from one complex type-2 pass with coefficients (v_x + i v_y) conj F(v)
// (see Evaluate). Kernel weights are computed once per evaluation and shared
// by both passes when they fit in kWeightBudgetBytes.
//
// Accuracy: the NUFFT error is relative to the sizes of the sums' terms, so
// F and the gradient agree with the direct engine to about `tolerance`
// relative to their norms on unoptimized sets, but on optimized sets, where
// F and the gradient are small sums of large terms, the relative error
// grows: at N = 256 after 1000 iterations (L_Spec 1e-4) tolerance 1e-9
// gives a gradient error of 6e-6, 1e-11 gives 9e-8. Hence the default
// 1e-11 (kernel width 12) for analyses; the optimizer, which needs only a
// descent direction, asks for 1e-7 (width 8) up to N = 4096 through
// SetTolerance (DefaultEngineTolerance in core/optimize/optimizer.h).
// Results do not depend on the thread count. Exactly `threads` threads do
// the work (FFTW runs single-threaded, one grid per thread).
class FastEngine final : public SpectralEngine {
 public:
  static constexpr double kDefaultTolerance = 1e-11;
  static constexpr size_t kWeightBudgetBytes = size_t{256} << 20;

  // weight_budget_bytes: above this, kernel weights are recomputed in the
  // type-2 pass instead of kept from the type-1 pass (large N).
  explicit FastEngine(int threads, double tolerance = kDefaultTolerance,
                      size_t weight_budget_bytes = kWeightBudgetBytes);
  ~FastEngine() override;
  std::string name() const override { return "fast"; }
  void SetFrequencies(const std::vector<Frequency>& k) override;
  void SetLossWeights(std::vector<double> weights) override;
  void Evaluate(const PointSet& points, bool with_gradient, SpectrumEvaluation* out) override;
  void EvaluateWeighted(const PointSet& points, const std::vector<double>& strengths,
                        std::vector<std::complex<double>>* spectrum) override;
  // Rebuilds the kernel (and the grids, which depend on its width) when the
  // tolerance asks for another width.
  void SetTolerance(double tolerance) override;

  // Introspection for tests and benchmarks.
  int kernel_width() const { return kernel_.width(); }
  size_t grid_count() const { return grids_.size(); }
  // Total cells of all grids.
  size_t grid_cells() const;

 private:
  struct Piece {
    std::unique_ptr<NufftGrid> grid;
    std::vector<uint32_t> members;        // indices into K
  };

  // The type-1 pass into `spectrum` (strengths: nullptr for all 1); keeps
  // the kernel weights for a type-2 pass when they fit and `keep_allowed`.
  void TypeOne(const PointSet& points, const double* strengths, bool keep_allowed,
               std::vector<std::complex<double>>* spectrum);
  // Partitions K into pieces and makes their grids for the current kernel.
  void BuildGrids();
  // Runs fn(job, worker) for jobs [0, weights.size()), each worker taking a
  // contiguous run of jobs of about equal total weight.
  void RunBalanced(const std::vector<size_t>& weights, const std::function<void(size_t, int)>& fn);
  // Runs fn(grid, begin, end, worker) over [0, count) of every grid, as one
  // parallel loop over all grids.
  void RunOverGrids(size_t count, const std::function<void(size_t, size_t, size_t, int)>& fn);

  ThreadPool pool_;
  EsKernel kernel_;
  size_t weight_budget_bytes_;
  std::vector<Frequency> k_;
  std::vector<double> weights_;  // loss weights over K; empty: all 1
  std::vector<Piece> grids_;
  // Per entry of K: its grid and its index among that grid's modes (for
  // the read-out in one loop).
  std::vector<uint32_t> grid_of_;
  std::vector<uint32_t> local_of_;
  std::vector<NufftGrid::Scratch> scratch_;           // one per worker
  std::vector<std::vector<std::complex<double>>> sums_;  // type-2 output, per grid
};

}  // namespace alignset

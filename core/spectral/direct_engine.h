#pragma once

#include <memory>

#include "core/spectral/spectral_engine.h"
#include "core/util/thread_pool.h"

namespace alignset {

// The reference engine: exact sums over every (point, frequency) pair,
// accumulated in double. exp(-2 pi i v.s) factors as
// exp(-2 pi i a x) * exp(-2 pi i b y); each factor is taken from sincos (never
// from a recurrence) for a block of points, so every term is accurate to a few
// ulps and the cost is one complex product per pair. Multithreaded over
// blocks of points.
class DirectEngine final : public SpectralEngine {
 public:
  explicit DirectEngine(int threads);
  std::string name() const override { return "direct"; }
  void SetFrequencies(const std::vector<Frequency>& k) override;
  void SetLossWeights(std::vector<double> weights) override;
  void Evaluate(const PointSet& points, bool with_gradient, SpectrumEvaluation* out) override;
  void EvaluateWeighted(const PointSet& points, const std::vector<double>& strengths,
                        std::vector<std::complex<double>>* spectrum) override;

 private:
  struct BlockTables {
    std::vector<double> xr, xi, yr, yi;
  };
  // The exp(-2 pi i a x) and exp(-2 pi i b y) tables of one block of points;
  // with strengths, the x table of point j is scaled by strengths[j].
  void FillBlock(const PointSet& points, const double* strengths, size_t block,
                 BlockTables* t) const;
  // The type-1 pass: F over K, with unit strengths when `strengths` is null.
  void Spectrum(const PointSet& points, const double* strengths,
                std::vector<std::complex<double>>* spectrum);

  ThreadPool pool_;
  std::vector<Frequency> k_;
  std::vector<double> weights_;  // empty: all 1
  int a_min_ = 0, a_max_ = 0, b_max_ = 0;
};

}  // namespace alignset

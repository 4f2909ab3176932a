#pragma once

#include <complex>
#include <memory>
#include <string>
#include <vector>

#include "core/spectral/frequency_set.h"
#include "core/util/point_set.h"
#include "core/util/status.h"

namespace alignset {

// What an engine computes for a point set S of N points over K, with loss
// weights w_v (1 unless SetLossWeights gave others):
//   F(v)   = sum_j exp(-2 pi i v.s_j)            (a type-1 NUFFT)
//   loss   = (1/|K|) sum over v in K of w_v |F(v)|^2 / N
//                                                 (L_Spec: with w = 1 the mean
//                                                  periodogram)
//   grad_j = d loss / d s_j
//          = 4 pi / (N |K|) * sum_v w_v v * Im(conj(F(v)) exp(-2 pi i v.s_j))
//                                                   (a type-2 NUFFT)
struct SpectrumEvaluation {
  std::vector<std::complex<double>> spectrum;  // F over K, in K's order
  double loss = 0.0;
  std::vector<Point2> gradient;  // empty unless requested
};

// The seam between the optimizer and the arithmetic: the direct reference
// engine, the fast NUFFT engine and the CUDA engine all implement it.
class SpectralEngine {
 public:
  virtual ~SpectralEngine() = default;
  virtual std::string name() const = 0;

  // Binds the frequency set; engines precompute what depends on K only.
  // The loss weights go back to 1.
  virtual void SetFrequencies(const std::vector<Frequency>& k) = 0;

  // Per-frequency weights of the loss, in K's order (one per member of the
  // bound K, finite and >= 0), or empty for all 1. They change the loss and
  // its gradient, never F.
  virtual void SetLossWeights(std::vector<double> weights) = 0;

  // Evaluates F and the loss at `points` (and the gradient if asked).
  virtual void Evaluate(const PointSet& points, bool with_gradient, SpectrumEvaluation* out) = 0;

  // F over K of points carrying real strengths,
  //   F(v) = sum_j strengths[j] exp(-2 pi i v.s_j),
  // the spectrum of a weighted sample (an integrand's samples, for direction
  // estimation). strengths.size() == points.size(). Only F: no loss, no
  // gradient.
  virtual void EvaluateWeighted(const PointSet& points, const std::vector<double>& strengths,
                                std::vector<std::complex<double>>* spectrum) = 0;

  // The relative accuracy the caller needs of F and the gradient from now
  // on (K and the loss weights are kept). An optimization needs a descent
  // direction, an analysis needs the numbers, so the optimizer asks for its
  // profile's tolerance (OptimizerOptions::engine_tolerance). Engines whose
  // accuracy is fixed ignore it: the direct engine is exact, the CUDA
  // engine has its own.
  virtual void SetTolerance(double tolerance) { (void)tolerance; }
};

enum class EngineKind { kAuto, kDirect, kFast, kCuda };

StatusOr<EngineKind> ParseEngineKind(const std::string& name);
std::string EngineKindName(EngineKind kind);

// Makes an engine of `kind` with `threads` CPU threads (<= 0: all cores).
// kAuto picks the best engine that is built and usable here.
StatusOr<std::unique_ptr<SpectralEngine>> MakeSpectralEngine(EngineKind kind, int threads);

}  // namespace alignset

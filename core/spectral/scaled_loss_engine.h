#pragma once

#include <memory>
#include <string>
#include <vector>

#include "core/spectral/spectral_engine.h"

namespace alignset {

// An engine whose loss (and gradient) is another engine's times a constant
// s; F is untouched. With it the optimizer minimises s L_Spec + c L_SW
// without a new option of its own: s = 0 leaves the sliced Wasserstein term
// alone, the supplement's Fig. 1 ablation (`alignset optimize
// --spectrum-weight 0`). It only rescales the weights the optimizer sets.
class ScaledLossEngine final : public SpectralEngine {
 public:
  ScaledLossEngine(SpectralEngine& inner, double scale) : inner_(inner), scale_(scale) {}
  std::string name() const override { return inner_.name(); }
  void SetFrequencies(const std::vector<Frequency>& k) override {
    size_ = k.size();
    inner_.SetFrequencies(k);
    SetLossWeights({});
  }
  void SetLossWeights(std::vector<double> weights) override {
    if (scale_ == 1.0) return inner_.SetLossWeights(std::move(weights));  // the inner, exactly
    if (weights.empty()) weights.assign(size_, 1.0);
    for (double& w : weights) w *= scale_;
    inner_.SetLossWeights(std::move(weights));
  }
  void Evaluate(const PointSet& points, bool with_gradient, SpectrumEvaluation* out) override {
    inner_.Evaluate(points, with_gradient, out);
  }
  void EvaluateWeighted(const PointSet& points, const std::vector<double>& strengths,
                        std::vector<std::complex<double>>* spectrum) override {
    inner_.EvaluateWeighted(points, strengths, spectrum);
  }
  void SetTolerance(double tolerance) override { inner_.SetTolerance(tolerance); }

 private:
  SpectralEngine& inner_;
  double scale_;
  size_t size_ = 0;
};

}  // namespace alignset

#include "render/prepass_reuse.h"

#include <alignset/aligned_sampler.h>

#include <vector>

#include "core/sampling/owen_sobol.h"

namespace alignset::render {

// The weights are the sampler library's (<alignset/aligned_sampler.h>): one
// home for the rule.
double PrepassWeight(uint32_t prepass_samples, uint32_t n) { return ::alignset::PrepassWeight(prepass_samples, n); }

double WithPrepass(const PixelDirection& d, double estimate, uint32_t n) {
  if (d.prepass_samples == 0) return estimate;
  const double w = PrepassWeight(d.prepass_samples, n);
  return w * d.prepass_mean + (1.0 - w) * estimate;
}

double ContinuedPrepass(const PixelIntegrand& f, const PixelDirection& d, uint32_t n) {
  const uint32_t p = d.prepass_samples;
  const PointSet points = OwenScrambledSobol(p + n, d.prepass_seed);
  std::vector<double> values;
  values.reserve(n);
  for (uint32_t k = p; k < p + n; ++k) values.push_back(f.Eval({points[k].x, points[k].y}));
  return ContinuedEstimate(d.prepass_mean, p, values);
}

namespace {

class Reused : public PixelSampler {
 public:
  Reused(std::unique_ptr<PixelSampler> inner, const std::vector<PixelDirection>* dirs, uint32_t n,
         bool continue_sequence)
      : inner_(std::move(inner)), dirs_(dirs), n_(n), continue_(continue_sequence) {}
  double Estimate(const PixelIntegrand& f, const PixelTask& t) const override {
    const PixelDirection& d = (*dirs_)[t.index];
    if (continue_ && d.kind == PixelDirection::Kind::kNone && d.prepass_samples > 0) {
      // A lattice has no sequence to continue: the sampler's own points alone.
      return d.prepass_lattice ? inner_->Estimate(f, t) : ContinuedPrepass(f, d, n_);
    }
    return WithPrepass(d, inner_->Estimate(f, t), n_);
  }

 private:
  std::unique_ptr<PixelSampler> inner_;
  const std::vector<PixelDirection>* dirs_;
  uint32_t n_;
  bool continue_;
};

}  // namespace

std::unique_ptr<PixelSampler> ReusePrepass(std::unique_ptr<PixelSampler> inner,
                                           const std::vector<PixelDirection>* dirs, uint32_t n,
                                           bool continue_sequence) {
  return std::make_unique<Reused>(std::move(inner), dirs, n, continue_sequence);
}

}  // namespace alignset::render

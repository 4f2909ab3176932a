#include "render/prepass_reuse.h"

#include <cmath>

namespace alignset::render {

double PrepassWeight(uint32_t prepass_samples, uint32_t n) {
  if (prepass_samples == 0) return 0.0;
  const double p = std::pow(static_cast<double>(prepass_samples), 1.5);
  return p / (p + 2.0 * std::pow(static_cast<double>(n), 1.5));
}

double WithPrepass(const PixelDirection& d, double estimate, uint32_t n) {
  if (d.prepass_samples == 0) return estimate;
  const double w = PrepassWeight(d.prepass_samples, n);
  return w * d.prepass_mean + (1.0 - w) * estimate;
}

namespace {

class Reused : public PixelSampler {
 public:
  Reused(std::unique_ptr<PixelSampler> inner, const std::vector<PixelDirection>* dirs, uint32_t n)
      : inner_(std::move(inner)), dirs_(dirs), n_(n) {}
  double Estimate(const PixelIntegrand& f, const PixelTask& t) const override {
    return WithPrepass((*dirs_)[t.index], inner_->Estimate(f, t), n_);
  }

 private:
  std::unique_ptr<PixelSampler> inner_;
  const std::vector<PixelDirection>* dirs_;
  uint32_t n_;
};

}  // namespace

std::unique_ptr<PixelSampler> ReusePrepass(std::unique_ptr<PixelSampler> inner,
                                           const std::vector<PixelDirection>* dirs, uint32_t n) {
  return std::make_unique<Reused>(std::move(inner), dirs, n);
}

}  // namespace alignset::render

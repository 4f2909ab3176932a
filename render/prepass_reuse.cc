#include "render/prepass_reuse.h"

#include <algorithm>
#include <cmath>

#include "core/sampling/owen_sobol.h"

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

double ContinuedPrepass(const PixelIntegrand& f, const PixelDirection& d, uint32_t n) {
  const uint32_t p = d.prepass_samples, total = p + n;
  const PointSet points = OwenScrambledSobol(total, d.prepass_seed);
  // The aligned power-of-two blocks of `total`, largest first; the pre-pass
  // must lie inside the first (its values are known by their mean only).
  std::vector<uint32_t> blocks;
  for (uint32_t bit = 1u << 31; bit != 0; bit >>= 1) {
    if (total & bit) blocks.push_back(bit);
  }
  if (p > blocks.front()) blocks.assign(1, total);  // a plain mean of every point
  double estimate = 0.0, weights = 0.0;
  uint32_t begin = 0;
  for (uint32_t size : blocks) {
    double sum = begin == 0 ? static_cast<double>(p) * d.prepass_mean : 0.0;
    for (uint32_t k = std::max(begin, p); k < begin + size; ++k) sum += f.Eval({points[k].x, points[k].y});
    const double w = std::pow(static_cast<double>(size), 3.0);
    estimate += w * sum / size;
    weights += w;
    begin += size;
  }
  return estimate / weights;
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

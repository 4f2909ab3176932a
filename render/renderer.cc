#include "render/renderer.h"

#include <cmath>

#include "render/parallel.h"
#include "core/sampling/periodic_blur.h"

namespace alignset::render {

std::vector<double> Render(const Scene& scene, const PixelSampler& sampler, uint64_t seed,
                           int threads) {
  std::vector<double> image(scene.size());
  const int w = scene.width();
  ParallelFor(scene.size(), threads, [&](size_t i) {
    PixelTask t;
    t.x = static_cast<int>(i % w);
    t.y = static_cast<int>(i / w);
    t.index = i;
    t.seed = seed;
    image[i] = sampler.Estimate(scene.Pixel(i), t);
  });
  return image;
}

double RenderPixel(const Scene& scene, const PixelSampler& sampler, int x, int y, uint64_t seed) {
  PixelTask t;
  t.x = x;
  t.y = y;
  t.index = static_cast<size_t>(y) * scene.width() + x;
  t.seed = seed;
  return sampler.Estimate(scene.Pixel(x, y), t);
}

ImageErrors MeasureErrors(const std::vector<double>& image, const std::vector<double>& reference,
                          const std::vector<PixelClass>& classes, int width, int height,
                          const std::vector<double>& sigmas) {
  ImageErrors r;
  std::vector<double> err(image.size());
  double edge = 0.0, smooth = 0.0, all = 0.0;
  for (size_t i = 0; i < image.size(); ++i) {
    err[i] = image[i] - reference[i];
    const double e2 = err[i] * err[i];
    all += e2;
    if (classes[i] == PixelClass::kEdge) {
      edge += e2;
      ++r.edge_pixels;
    } else if (classes[i] == PixelClass::kSmooth) {
      smooth += e2;
      ++r.smooth_pixels;
    }
  }
  r.mse_all = all / static_cast<double>(image.size());
  r.mse_edge = r.edge_pixels ? edge / r.edge_pixels : 0.0;
  r.mse_smooth = r.smooth_pixels ? smooth / r.smooth_pixels : 0.0;
  for (double sigma : sigmas) {
    double s = 0.0;
    for (double v : PeriodicGaussianBlur(err, width, height, sigma)) s += v * v;
    r.blur_rms.push_back(std::sqrt(s / static_cast<double>(err.size())));
  }
  return r;
}

}  // namespace alignset::render

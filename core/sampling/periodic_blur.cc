#include "core/sampling/periodic_blur.h"

#include <cmath>

namespace alignset {

std::vector<double> PeriodicGaussianKernel(double sigma, int period) {
  std::vector<double> k(period, 0.0);
  if (sigma <= 0.0) {
    k[0] = 1.0;
    return k;
  }
  const int radius = static_cast<int>(std::ceil(3.0 * sigma));
  double sum = 0.0;
  for (int m = -radius; m <= radius; ++m) {
    const double w = std::exp(-0.5 * m * m / (sigma * sigma));
    k[((m % period) + period) % period] += w;
    sum += w;
  }
  for (double& v : k) v /= sum;
  return k;
}

std::vector<double> RingAutocorrelation(const std::vector<double>& k) {
  const int n = static_cast<int>(k.size());
  std::vector<double> out(n, 0.0);
  for (int d = 0; d < n; ++d) {
    for (int m = 0; m < n; ++m) out[d] += k[m] * k[(m + d) % n];
  }
  return out;
}

std::vector<double> PeriodicSeparableConvolve(const std::vector<double>& image, int w, int h,
                                              const std::vector<double>& kx,
                                              const std::vector<double>& ky) {
  std::vector<double> tmp(image.size(), 0.0), out(image.size(), 0.0);
  for (int y = 0; y < h; ++y) {
    for (int d = 0; d < w; ++d) {
      if (kx[d] == 0.0) continue;
      for (int x = 0; x < w; ++x) tmp[y * w + (x + d) % w] += kx[d] * image[y * w + x];
    }
  }
  for (int d = 0; d < h; ++d) {
    if (ky[d] == 0.0) continue;
    for (int y = 0; y < h; ++y) {
      const int ty = (y + d) % h;
      for (int x = 0; x < w; ++x) out[ty * w + x] += ky[d] * tmp[y * w + x];
    }
  }
  return out;
}

std::vector<double> PeriodicGaussianBlur(const std::vector<double>& image, int w, int h,
                                         double sigma) {
  return PeriodicSeparableConvolve(image, w, h, PeriodicGaussianKernel(sigma, w),
                                   PeriodicGaussianKernel(sigma, h));
}

}  // namespace alignset

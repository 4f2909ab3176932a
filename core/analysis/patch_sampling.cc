#include "core/analysis/patch_sampling.h"

#include "core/util/hash.h"

namespace alignset {

GridPatch PointSampledGrid(const Integrand2& f, int width, int height) {
  GridPatch g{width, height, {}};
  g.values.resize(static_cast<size_t>(width) * height);
  for (int j = 0; j < height; ++j) {
    for (int i = 0; i < width; ++i) {
      g.values[static_cast<size_t>(j) * width + i] = f({(i + 0.5) / width, (j + 0.5) / height});
    }
  }
  return g;
}

GridPatch RandomSampledGrid(const Integrand2& f, int width, int height, int spp, uint64_t seed) {
  GridPatch g{width, height, {}};
  g.values.resize(static_cast<size_t>(width) * height);
  Pcg32 rng(seed);
  for (int j = 0; j < height; ++j) {
    for (int i = 0; i < width; ++i) {
      double sum = 0.0;
      for (int s = 0; s < spp; ++s) {
        const double x = (i + rng.NextDouble()) / width;
        const double y = (j + rng.NextDouble()) / height;
        sum += f({x, y});
      }
      g.values[static_cast<size_t>(j) * width + i] = sum / spp;
    }
  }
  return g;
}

SampledPatch RandomSamples(const Integrand2& f, int count, uint64_t seed) {
  SampledPatch s;
  s.points.resize(count);
  s.values.resize(count);
  Pcg32 rng(seed);
  for (int j = 0; j < count; ++j) {
    s.points[j] = {rng.NextDouble(), rng.NextDouble()};
    s.values[j] = f(s.points[j]);
  }
  return s;
}

}  // namespace alignset

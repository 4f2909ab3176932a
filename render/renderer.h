#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include "render/pixel_samplers.h"
#include "render/scene.h"

namespace alignset::render {

// Every pixel's estimate, row by row (y * W + x), on `threads` threads.
std::vector<double> Render(const Scene& scene, const PixelSampler& sampler, uint64_t seed,
                           int threads);

// One pixel's estimate (tests render a few pixels only).
double RenderPixel(const Scene& scene, const PixelSampler& sampler, int x, int y, uint64_t seed);

// Errors of an image against the exact reference.
struct ImageErrors {
  double mse_all = 0.0;
  double mse_edge = 0.0;    // over PixelClass::kEdge pixels
  double mse_smooth = 0.0;  // over PixelClass::kSmooth pixels
  size_t edge_pixels = 0;
  size_t smooth_pixels = 0;
  // Seed 003's criterion on the rendering: RMS of k_sigma * (I - I_ref) over
  // the image (periodic blur), one per entry of `sigmas`.
  std::vector<double> blur_rms;
};
ImageErrors MeasureErrors(const std::vector<double>& image, const std::vector<double>& reference,
                          const std::vector<PixelClass>& classes, int width, int height,
                          const std::vector<double>& sigmas);

}  // namespace alignset::render

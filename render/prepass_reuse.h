#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "render/direction.h"
#include "render/pixel_samplers.h"

namespace alignset::render {

// Every sample counted, none wasted: a pre-pass of M Owen-scrambled Sobol
// points (samplesM; Prepass::Reusable) is itself an unbiased estimate of the
// pixel, independent of the sampler's own randomization, so the two combine
// into one unbiased estimate
//
//   w * prepass_mean + (1 - w) * sampler_estimate,
//
// as long as w does not depend on the pixel's samples. A weight read from
// the pre-pass's values (its direction, its confidence, its spread) would
// correlate with prepass_mean and bias the sum, so w depends on the two
// counts alone: the inverse-variance weight of two estimators whose
// variance falls like n^-1.5 (a stratified set on a discontinuity), the
// sampler's constant half the pre-pass's,
//
//   w = P^1.5 / (P^1.5 + 2 N^1.5).
//
// The factor 2 is the aligned sets' gain over Owen-Sobol on a synthetic
// step edge at small N (docs/results.md; the lattices' is larger), a
// property of the sampler, not of a scene. Where the sampler is Owen-Sobol
// (a pixel without a direction) the two are equal and this weight costs
// 11% against the equal one's optimum at P = N; where the sampler gains
// more than 2x, it gives away a little of that gain; neither touches the
// unbiasedness. At P = N, w = 1/3; at P = 256, N = 4096, w = 1/129, where
// the pre-pass has next to nothing left to add.
double PrepassWeight(uint32_t prepass_samples, uint32_t n);

// The combined estimate of one pixel; `estimate` alone when the pixel has
// no reusable pre-pass (prepass_samples == 0).
double WithPrepass(const PixelDirection& d, double estimate, uint32_t n);

// Wraps a sampler of N points that reads `dirs` (the pre-pass's map) so that
// each pixel's estimate includes its pre-pass.
std::unique_ptr<PixelSampler> ReusePrepass(std::unique_ptr<PixelSampler> inner,
                                           const std::vector<PixelDirection>* dirs, uint32_t n);

}  // namespace alignset::render

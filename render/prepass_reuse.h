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

// A pixel the pre-pass found no direction in gets Owen-Sobol from the
// samplers that read directions (aligned, aligned-lattice). Two independent
// Owen-Sobol sets of P and N points, weighted as above, are a poor use of
// P + N samples on a smooth pixel: a net of P + N points converges like
// n^-3 there, so the weighted pair is 4.4 times Owen-Sobol's squared error
// at P = N = 256 (measured on the scenes' smooth pixels, 0.23x). So the
// pixel continues the pre-pass's own sequence to T = P + N points. Where T
// is a power of two they are one net and the estimate is their mean,
// exactly Owen-Sobol at T. Where it is not, the plain mean is a poor
// estimate on a smooth pixel (at T = 320 = 256 + 64 the last 64 points, a
// net four times coarser, carry most of the error: Owen-Sobol at 320 is
// about 3x its squared error at 256 there), so each aligned power-of-two
// block of the T points (each a net: the index shuffle maps aligned blocks
// to aligned blocks) is weighted by its size cubed, the n^-3 of a smooth
// pixel: at T = 320 the 256-block gets 64/65. A fixed weight per block
// keeps the sum unbiased; on a pixel with an edge the pre-pass missed it
// gives up little (the blocks' n^-1.5 weights would be 8:1 at 320).
//
// The price: the choice between the two branches is read from the
// pre-pass, and the continued points are not independent of it (they fill
// the strata it left), so on a pixel where the pre-pass finds an edge in
// some draws and not in others the estimate has a selection bias. It is
// consistent (the bias falls with N) and measured small: 2-8% of the
// estimate's RMS error on such borderline pixels of both scenes at N = 256
// and 1024, with the pixel's own fit deciding (edges64, edges256; a squared
// bias under 1% of the MSE; the test holds it under a fifth,
// tests/render/prepass_reuse_test.cc). The pooled pre-pass (nedgesM) also
// reads the neighbours' independent samples, which only weakens the link. A pixel whose branch never
// changes (a smooth pixel, a clear edge) keeps an unbiased estimate.
// kUnbiased (`--reuse-prepass unbiased`) keeps the count weights on every
// pixel.
double ContinuedPrepass(const PixelIntegrand& f, const PixelDirection& d, uint32_t n);

// Wraps a sampler of N points that reads `dirs` (the pre-pass's map) so that
// each pixel's estimate includes its pre-pass; with `continue_sequence`
// (the sampler's own direction-less branch is Owen-Sobol) a direction-less
// pixel takes ContinuedPrepass instead, or, after a lattice pre-pass
// (render/prepass_lattice.h), which has no sequence to continue, the
// sampler's own Owen-Sobol estimate alone.
std::unique_ptr<PixelSampler> ReusePrepass(std::unique_ptr<PixelSampler> inner,
                                           const std::vector<PixelDirection>* dirs, uint32_t n,
                                           bool continue_sequence);

}  // namespace alignset::render

#pragma once

// The per-pixel recipe of alignset's rendered gains, for any renderer: a
// pre-pass, the pixel's edge direction from it (pooled with its
// neighbours'), the aligned set for that direction from a table file
// (<alignset/set_table.h>), and the rule that folds the pre-pass back into
// the pixel's estimate. No server and no RPC at render time.
//
// A pixel's life, with M = prepass_samples() and N = n():
//
//   1. PrepassPoints(x, y)       M points in the pixel's [0,1)^2; the
//                                renderer evaluates its integrand there.
//   2. Plan(x, y, block)         the pixel's direction(s) and set, from the
//                                pre-pass values of the block of
//                                (2R + 1)^2 pixels around it, R = block_radius()
//                                (a tiled renderer runs the pre-pass over the
//                                tile and an apron of R pixels first).
//   3. MainPoints(plan)          N points; the renderer evaluates them.
//   4. Estimate(plan, pre, main) the pixel's value from both sets of values.
//
// Every sample counts: the pixel spends M + N evaluations, and the estimate
// uses all of them. Under PrepassReuse::kUnbiased (the default) the estimate
// is unbiased for every pixel: the weights of the two means depend on M and
// N alone, never on the values, and the main points are independent of the
// pre-pass. A pixel without a dominant direction (smooth, textured, noise)
// falls back to N Owen-scrambled Sobol points of its own.
//
// The points of a pixel are a function of (options.seed, x, y): the same on
// every thread, machine and run. The sampler is immutable after Create and
// safe to share between threads; each thread keeps its own Scratch, which
// holds every buffer a plan needs (the core's edge-line fit's included), grown
// on its first pixel for the largest block of its M: no pixel after that
// allocates (tested by counting every operator new over whole frames).

#include <alignset/point_set.h>
#include <alignset/prepass_fit.h>
#include <alignset/set_choice.h>
#include <alignset/set_table.h>
#include <alignset/status.h>

#include <cstdint>
#include <memory>
#include <span>
#include <string>

namespace alignset {

// How the pre-pass enters the estimate.
//  - kUnbiased: w * mean(pre-pass) + (1 - w) * mean(main) on every pixel,
//    w = M^1.5 / (M^1.5 + 2 N^1.5) (the inverse-variance weight of two
//    stratified estimators on an edge, the aligned set's constant half the
//    pre-pass's). Unbiased.
//  - kContinue: alignset render's measured default. A pixel with a
//    direction as above; a direction-less pixel after an Owen-Sobol pre-pass
//    continues the pre-pass's own sequence to M + N points (one net where
//    M + N is a power of two: Owen-Sobol at M + N on smooth pixels), after a
//    lattice pre-pass takes its own N Owen-Sobol points alone. The branch is
//    read from the pre-pass, so a pixel whose direction comes and goes with
//    the pre-pass's draw carries a small selection bias (2-8% of its RMS
//    error, measured; docs/rendering.md).
enum class PrepassReuse { kUnbiased, kContinue };

// The pre-pass's weight beside N main points under kUnbiased (and on every
// pixel with a set under kContinue): M^1.5 / (M^1.5 + 2 N^1.5).
double PrepassWeight(uint32_t prepass_samples, uint32_t n);
// kContinue's estimate of a direction-less pixel after an Owen-Sobol
// pre-pass: the pre-pass's M values (by their mean) and the next points of
// its sequence, each aligned power-of-two block of the M + N weighted by its
// size cubed (the n^-3 of a smooth pixel; a plain mean of all when the
// pre-pass spans blocks).
double ContinuedEstimate(double prepass_mean, uint32_t prepass_samples, std::span<const double> continued_values);

// A served set's points for one pixel: a lattice (set.lattice_generator)
// rebuilt under `shift` (its realization 0 moved by the shift, folded after
// it for a tent-lattice), any other set shifted on the torus. out.size() is
// the set's n. The points AlignedSampler::MainPoints gives a planned pixel.
void SetPixelPoints(const TableSet& set, Point2 shift, std::span<Point2> out);
// A direction-less pixel's own N Owen-scrambled Sobol points under a
// render's seed (AlignedSampler's fallback).
void FallbackPixelPoints(uint64_t seed, uint32_t x, uint32_t y, std::span<Point2> out);

struct AlignedSamplerOptions {
  uint32_t n = 256;                       // main points per pixel: an N of the table
  std::string construction = "lattice";   // the table's construction to read
  PixelDomain domain = PixelDomain::kFootprint;
  uint32_t image_width = 0;               // pixels per row (the pixel seeds are y * width + x)
  uint64_t seed = 1;                      // a render's seed: another seed, another independent image
  // 0: N / 4, within [16, 256] (64 at N = 256, 256 from N = 1024: alignset
  // render's measured default).
  uint32_t prepass_samples = 0;
  // The pre-pass's points: a shifted rank-1 lattice (crossings more evenly
  // spread along an edge) or Owen-Sobol points. Auto: the lattice up to
  // N = 1024 and on a shared domain (measured, docs/rendering.md).
  enum class PrepassPoints { kAuto, kLattice, kOwenSobol };
  PrepassPoints prepass_points = PrepassPoints::kAuto;
  // The stacked block's radius on a shared domain; 0: 2 up to N = 1024, 1
  // above (measured). On footprints the block is always 3 x 3.
  int stack_radius = 0;
  bool two_directions = true;  // a pixel with two edges reads a two-direction set
  PrepassReuse reuse = PrepassReuse::kUnbiased;
};

// What Plan decided for one pixel.
struct PixelPlan {
  uint32_t x = 0, y = 0;
  int directions = 0;  // 0, 1 or 2 dominant directions found
  double theta1_deg = 0.0, theta2_deg = 0.0;  // the edge normals, degrees in [0, 180)
  SetChoice choice;    // kFallback: the pixel's own Owen-Sobol points
  // The table had no two-direction set for the pixel's pair: it reads the
  // stronger direction's one-direction set (counted in Scratch::stats).
  bool pair_fell_back = false;
  TableSet set;        // the aligned set (choice != kFallback)
  Point2 shift;        // the pixel's Cranley-Patterson shift of that set
  // Where the main points come from: the set under the shift, the pixel's
  // own Owen-Sobol points, or the pre-pass's sequence continued.
  enum class Main { kSet, kOwenSobol, kContinued };
  Main main = Main::kOwenSobol;
  uint64_t main_seed = 0;
};

class AlignedSampler {
 public:
  // One per thread: the buffers a plan needs, and counts of what happened.
  class Scratch {
   public:
    struct Stats {
      uint64_t pixels = 0, with_direction = 0, two_directions = 0, pair_fell_back = 0, fit_refused = 0;
    };
    const Stats& stats() const { return stats_; }

   private:
    friend class AlignedSampler;
    PrepassFit::Scratch fit_;
    Stats stats_;
  };

  // INVALID_ARGUMENT for options out of range, NOT_FOUND when the table has
  // no one-direction sets of `n` and `construction` (naming what it has).
  static StatusOr<AlignedSampler> Create(std::shared_ptr<const SetTable> table, const AlignedSamplerOptions& options);
  // An empty sampler (what a failed Create holds); only Create makes one to use.
  AlignedSampler() = default;

  const AlignedSamplerOptions& options() const { return options_; }
  uint32_t n() const { return options_.n; }
  uint32_t prepass_samples() const { return fit_.prepass_samples(); }
  int block_radius() const { return fit_.block_radius(); }
  int block_side() const { return fit_.block_side(); }
  bool lattice_prepass() const { return fit_.options().lattice_points; }
  // The direction fit this sampler plans with.
  const PrepassFit& fit() const { return fit_; }

  // The pixel's pre-pass points (out.size() == prepass_samples()).
  void PrepassPoints(uint32_t x, uint32_t y, std::span<Point2> out) const;
  // The pixel's plan from the pre-pass values of its block: block_side()^2
  // spans, row by row from (x - R, y - R), each the M values of that pixel
  // in PrepassPoints order; an empty span for a pixel outside the image.
  // INVALID_ARGUMENT for a block of the wrong shape.
  StatusOr<PixelPlan> Plan(uint32_t x, uint32_t y, std::span<const std::span<const double>> block,
                           Scratch& scratch) const;
  // The plan's main points (out.size() == n()); with out.size() < n(), the
  // first out.size() of them.
  void MainPoints(const PixelPlan& plan, std::span<Point2> out) const;
  // The pixel's estimate from its pre-pass values (M) and main values (N),
  // or the first k < N main values: the pre-pass then weighs as beside k
  // (PrepassWeight(M, k)).
  double Estimate(const PixelPlan& plan, std::span<const double> prepass_values,
                  std::span<const double> main_values) const;
  // Whether every prefix of the main points is a good set of its own (the
  // construction is progressive, "lattice-sequence"; the Owen-Sobol fallback
  // always is): a renderer may stop a pixel after any k main points, reading
  // the first k of MainPoints, and still get the construction's gain at k
  // (adaptive sampling, a progressive preview). A fixed-size set's prefix is
  // unbiased too, but only a part of a set made for N.
  bool progressive() const { return progressive_; }
  // The pre-pass's weight in a kUnbiased estimate.
  double PrepassWeight() const { return weight_; }

 private:
  std::shared_ptr<const SetTable> table_;
  // The table's sections of (n, construction), resolved at Create: a pixel's
  // lookup builds no key.
  SetTable::Sections sections_;
  AlignedSamplerOptions options_;
  PrepassFit fit_;
  double weight_ = 0.0;
  bool progressive_ = false;
};

}  // namespace alignset

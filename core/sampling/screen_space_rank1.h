#pragma once

#include <cstdint>
#include <vector>

#include "core/util/point_set.h"
#include "core/util/status.h"

namespace alignset {

// The rank-1 lattice screen-space sampler of Belcour and Heitz ("Lessons
// Learned and Improvements when Building Screen-Space Samplers with
// Blue-Noise Error Distribution"): every pixel p of a
// tile uses the same rank-1 lattice, shifted by its own toroidal shift,
//   sample(p, k) = frac(k * (1, g) / N + shift(p)),
// with g = Rank1Generator(N). The shifts are a fixed multiset of uniform
// random shifts whose assignment to pixels is optimized by pairwise swaps, so
// that the pixels' errors on random Heaviside integrands form blue noise
// across the tile: neighbouring pixels err in opposite directions, and a
// blur (a denoiser, or the eye) cancels them.
//
// Each pixel's estimate is a CP-shifted lattice rule, exactly as
// `rank1-lattice` with per-pixel shifts; only the joint distribution of the
// errors across the screen changes.

struct ShiftTile {
  int size = 0;                // size x size pixels
  std::vector<Point2> shifts;  // row-major, y * size + x
  // The shift of pixel (x, y), the tile repeating over the screen.
  Point2 At(int x, int y) const {
    const int tx = ((x % size) + size) % size, ty = ((y % size) + size) % size;
    return shifts[static_cast<size_t>(ty) * size + tx];
  }
};

class ScreenSpaceRank1 {
 public:
  ScreenSpaceRank1(uint32_t n, ShiftTile tile);
  uint32_t n() const { return n_; }
  uint32_t generator() const { return g_; }
  const ShiftTile& tile() const { return tile_; }
  // The N samples of pixel (x, y), each further shifted by `extra` (a shift
  // shared by the whole screen: randomizes a render without breaking the
  // tile's structure).
  PointSet PixelSet(int x, int y, Point2 extra = {}) const;

 private:
  uint32_t n_;
  uint32_t g_;
  ShiftTile tile_;
};

struct ShiftTileOptions {
  int size = 64;                // tile side in pixels
  int test_integrands = 128;    // random Heaviside half-planes
  double sigma = 1.0;           // the Gaussian blur (pixels) the loss is measured after
  int sweeps = 32;              // swap proposals per pixel
  int neighbourhood = 6;        // a proposal pairs a pixel with one at most this far away
  uint64_t seed = 1;
};

struct ShiftTileReport {
  double loss_before = 0.0;  // sum over test integrands of ||k_sigma * e_t||^2 / pixels
  double loss_after = 0.0;
  uint64_t proposals = 0;
  uint64_t accepted = 0;
};

// Uniform random shifts, then greedy pairwise swaps that lower
//   L = sum_t ||k_sigma * e_t||^2,
// e_t(p) = the error of pixel p's shifted lattice on test integrand t (the
// seed's criterion before the variance is taken). A swap of p and q changes
// e_t at two pixels only, so its effect on L is found in O(T) from the kept
// maps C_t = (k * k) * e_t (the blur's autocorrelation applied to the
// errors), which are updated locally when a swap is accepted.
// Deterministic for (n, options). INVALID_ARGUMENT for n outside
// [1, 2^20], a size outside [2, 256], or no test integrands.
StatusOr<ShiftTile> OptimizeShiftTile(uint32_t n, const ShiftTileOptions& options,
                                      ShiftTileReport* report = nullptr);

// Seed 003's blur criterion on test integrands: the mean over `test_integrands`
// random Heaviside half-planes (drawn from `seed`) of Var_p[(k_sigma * e_t)(p)],
// the variance across the tile of the blurred per-pixel errors.
double TileBlurCriterion(uint32_t n, const ShiftTile& tile, double sigma, int test_integrands,
                         uint64_t seed);

// The error maps behind both: maps[t][y * size + x] is the error of pixel
// (x, y)'s shifted lattice on the t-th of `test_integrands` random Heaviside
// half-planes drawn from `seed` (the same draw OptimizeShiftTile makes from
// options.seed).
std::vector<std::vector<double>> TileErrorMaps(uint32_t n, const ShiftTile& tile,
                                               int test_integrands, uint64_t seed);

// A tile of independent uniform shifts (the starting point, and the
// "rank-1 lattice with per-pixel CP shifts" baseline).
ShiftTile RandomShiftTile(int size, uint64_t seed);

}  // namespace alignset

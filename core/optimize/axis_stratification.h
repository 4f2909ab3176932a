#pragma once

#include <cstdint>
#include <utility>
#include <vector>

#include "core/util/point_set.h"

namespace alignset {

// Keeps a set stratified along both axes: after each optimizer step, the
// point of rank r along x is clamped into the column [r/N, (r+1)/N), and
// likewise along y, so every column and every row of width 1/N holds exactly
// one point (a Latin hypercube), as in the Owen-scrambled Sobol start.
//
// Why: the variance of an axis-aligned edge (the square's own edges, and
// every horizontal or vertical edge in a pixel) is decided by the 1-D
// projections at the scale 1/N, far beyond the suppressed strips (|v| <= L
// ~ N/16). The sliced Wasserstein term pulls projections towards the stratum
// centres but only softly: an optimized set without the clamp leaves 10% of
// the columns empty at N = 1024, and its axis edges then lose to Owen-Sobol's
// jittered strata. The clamp keeps the ranks' order, so it is a projection
// onto the stratified sets that moves each coordinate as little as possible.
class AxisStratification {
 public:
  // Clamps `points` in place (coordinates in [0,1)); with a margin m, into
  // [(r + m)/N, (r + 1 - m)/N) instead, the central part of each stratum.
  void Apply(PointSet* points, double margin = 0.0);

  // Releases what every Apply rebuilds (the sort keys, the strata bounds),
  // for a run that is paused; the orders stay, so the next sort is warm.
  void ReleaseScratch();
  // What it holds between calls, in bytes.
  size_t HeldBytes() const;

 private:
  // Sorts from the previous call's order (nearly sorted between steps). The
  // orders are the state; keyed_ is scratch, the keys of one axis at a time.
  std::vector<uint32_t> order_x_, order_y_;
  std::vector<std::pair<double, uint32_t>> keyed_;
  // The strata's clamp bounds for the last N and margin.
  std::vector<double> lo_, hi_;
  double bounds_margin_ = -1.0;
};

// The number of empty columns plus empty rows of width 1/N (0 for a
// stratified set), for tests and diagnostics.
size_t EmptyAxisStrata(const PointSet& points);

}  // namespace alignset

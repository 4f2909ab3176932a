#pragma once

#include <vector>

#include "core/analysis/convex_polygon.h"
#include "core/analysis/integer_indicator_spectrum.h"

namespace alignset {

// The tent phi(u) = 1 - |2 u - 1| maps each quadrant of the square onto the
// whole square, so f(phi(u)) is f's indicator region copied into the four
// quadrants, halved and mirrored: these are the copies of polygon p (u = x / 2
// or 1 - x / 2 in each coordinate), counter-clockwise.
std::vector<Polygon> TentFoldedImages(const Polygon& p);

// |g^(h)|^2 at integer h != 0 for g = f o phi, f the indicator of a polygon:
// the variance of a lattice shifted before the fold is the sum of these over
// its dual points, as a plain lattice's is of |f^(h)|^2
// (core/analysis/lattice_variance.h). g^(h) is f's cosine coefficient
// int f(x, y) cos(pi h_x x) cos(pi h_y y), the four copies' coefficients
// added.
// The copies come in pairs under the point reflection u -> (1, 1) - u
// (both mirrors), whose coefficients are conjugate, so two of them carry the
// whole (SymmetricUnionEnergy).
class FoldedIndicatorSpectrum {
 public:
  FoldedIndicatorSpectrum(const Polygon& polygon, int radius, bool tabulate = true);
  double Energy(int hx, int hy) const;

 private:
  std::vector<IntegerIndicatorSpectrum> parts_;  // the copies with no mirror and with x mirrored
};

// The two copies FoldedIndicatorSpectrum keeps: TentFoldedImages' first and
// third (no mirror; x mirrored).
std::vector<Polygon> TentFoldedHalf(const Polygon& p);

}  // namespace alignset

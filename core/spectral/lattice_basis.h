#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include "core/spectral/frequency_set.h"

namespace alignset {

// An integer basis (p, q) of Z^2 (|det| = 1): every frequency is
// v = w1 p + w2 q with integer w. Since v.s = w1 (p.s) + w2 (q.s), the
// spectrum of S at v is the spectrum of the mapped set u = (p.s, q.s) mod 1
// at w, and s -> u is a bijection of the torus. A strip of frequencies along
// an oblique direction becomes, in a basis with p close to that direction, a
// thin box of w's: the NUFFT grid of the strip.
struct LatticeBasis {
  int64_t p1 = 1, p2 = 0;
  int64_t q1 = 0, q2 = 1;

  int64_t det() const { return p1 * q2 - p2 * q1; }
  // Coordinates of v in this basis (det is +-1, so 1/det = det).
  int64_t W1(int64_t a, int64_t b) const { return (q2 * a - q1 * b) * det(); }
  int64_t W2(int64_t a, int64_t b) const { return (p1 * b - p2 * a) * det(); }
  // The same basis with p and q exchanged (w1 and w2 swap).
  LatticeBasis Swapped() const { return {q1, q2, p1, p2}; }
};

// The box |w1| <= m1, |w2| <= m2 a set of frequencies occupies in a basis.
struct BasisBox {
  LatticeBasis basis;
  int64_t m1 = 0;
  int64_t m2 = 0;
};

// Convex hull (counter-clockwise, no collinear points) of integer points.
std::vector<Frequency> ConvexHull(std::vector<Frequency> points);

// The box of the centrally symmetric set +-hull (hull: vertices of the
// convex hull of one side; the box of +-points equals the box of +-hull).
BasisBox BoxInBasis(const std::vector<Frequency>& hull, const LatticeBasis& basis);

// The basis among those whose first vector p is primitive with
// max(|p1|, |p2|) <= max_component and lies within the angular window
// [angle_lo - margin, angle_hi + margin] (radians, taken modulo pi; the
// window may wrap) that minimizes cost(m1, m2) of the box of +-hull, the
// second vector q chosen (over all q completing p) to minimize m1. The
// identity basis is always a candidate.
BasisBox BestBasis(const std::vector<Frequency>& hull, double angle_lo, double angle_hi,
                   double margin, int max_component,
                   const std::function<double(int64_t, int64_t)>& cost);

}  // namespace alignset

#pragma once

// A served lattice's points under a shift of the renderer's own: the
// per-pixel randomization of a "lattice" or "tent-lattice" set.
//
// The server tells the served set's generator g (SetInfo::lattice_generator):
// the set is the rank-1 lattice {frac(i (1, g) / N + s)} for some shift s, and
// a tent-lattice that lattice folded by phi(u) = 1 - |2u - 1| in each
// coordinate after the shift. Any shift s keeps the lattice's structure, and
// a uniformly random one makes the estimate unbiased. For a tent-lattice the
// shift must come before the fold: a Cranley-Patterson shift of the served
// (folded) points is unbiased too, but integrates smooth functions that are
// not periodic on the pixel only about as well as Owen-Sobol, where the fold
// after the shift keeps them far better. So a renderer that shifts per pixel
// builds each pixel's points here, with PixelShift (<alignset/pixel_shift.h>)
// as the shift, instead of ShiftPoint on the served points.
//
// Header-only.

#include <cmath>
#include <cstdint>

#include <alignset/point_set.h>

namespace alignset {

// Point i (0 <= i < n, n >= 1) of the lattice of generator g shifted by
// `shift` (both coordinates in [0, 1)), folded after the shift when
// `folded`. No checks here (an inner loop): g comes from the server, the
// shift from PixelShift.
inline Point2 ShiftedLatticePoint(uint32_t n, uint32_t g, uint32_t i, Point2 shift, bool folded) {
  const double inv = 1.0 / n;
  double x = static_cast<double>(i) * inv + shift.x;
  double y = static_cast<double>((static_cast<uint64_t>(i) * g) % n) * inv + shift.y;
  x -= std::floor(x);
  y -= std::floor(y);
  if (folded) {
    // The fold maps [0, 1) onto [0, 1]; 1 itself (u = 1/2) stays inside the
    // half-open square.
    const double below_one = std::nextafter(1.0, 0.0);
    x = std::fmin(1.0 - std::fabs(2.0 * x - 1.0), below_one);
    y = std::fmin(1.0 - std::fabs(2.0 * y - 1.0), below_one);
  }
  return {x, y};
}

// All n points, in lattice order.
inline PointSet ShiftedLatticePoints(uint32_t n, uint32_t g, Point2 shift, bool folded) {
  PointSet points(n);
  for (uint32_t i = 0; i < n; ++i) points[i] = ShiftedLatticePoint(n, g, i, shift, folded);
  return points;
}

}  // namespace alignset

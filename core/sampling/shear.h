#pragma once

#include "core/util/point_set.h"

namespace alignset {

// Algorithm 2 of the paper (after Singh & Jarosz 2017): shears a set whose
// spectrum is dark along the axes so that the dark axis nearest to θ moves
// onto θ. θ is in degrees, spectral convention: the edge normal.
//
// With t = θ in radians, p = (tan t, 0) when |cos t| >= 1/sqrt(2), else
// (0, cot t), and every point s -> (s - p * (s.y, s.x)) mod 1. On the torus a
// shear by a non-integer factor is not a bijection of the lattice of
// frequencies: mod 1 turns the square's boundary into a slanted seam, which
// is why a sheared set gains little (a baseline, method.md section 2).
//
// Why it moves the dark axis: x' = x - tan(t) y maps frequency u to
// v = (u.x, u.y + tan(t) u.x) in the sheared spectrum, so the dark x-axis
// u = (1, 0) becomes the direction (1, tan t), i.e. θ.
PointSet Shear(const PointSet& points, double theta_deg);

}  // namespace alignset

#pragma once

#include <complex>

#include "core/analysis/convex_polygon.h"

namespace alignset {

// The Fourier transform of a linear function restricted to a polygon,
//   H(v) = integral over P of h(x) exp(-2 pi i v.x) dx,   h(x) = a + g.x,
// in closed form, for any real frequency v (integer v give the Fourier-series
// coefficients of the periodized function on the torus).
//
// For v != 0, h exp(-2 pi i v.x) is the divergence of (alpha h + beta) v
// exp(-2 pi i v.x) with alpha = i / (2 pi |v|^2) and
// beta = (g.v) / (4 pi^2 |v|^4), so by the divergence theorem H(v) is a sum
// over the edges of 1-D integrals of (linear) x exp(linear), each in closed
// form (with a Taylor series where the closed form cancels; below |v| = 1/2,
// where the edge sum itself cancels, by quadrature). Decays like
// 1/|v| along the normals of the edges and like 1/|v|^2 elsewhere: the
// spectrum of a discontinuity.
std::complex<double> LinearPolygonFourier(const Polygon& polygon, const LinearFunction& h,
                                          Vec2 v);

}  // namespace alignset

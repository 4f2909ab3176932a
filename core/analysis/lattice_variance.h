#pragma once

#include <cstdint>
#include <vector>

#include "core/analysis/convex_polygon.h"
#include "core/analysis/integrand.h"
#include "core/spectral/frequency_set.h"

namespace alignset {

// The rank-1 lattice {frac(i (1, g) / N + shift)}, i = 0..N-1, has the point
// spectrum P(v) = N on its dual lattice L* = {h in Z^2 : h_x + g h_y = 0 mod N}
// and 0 elsewhere, whatever the shift. Eq. 18 therefore collapses to
//   Var[CP-rotated estimate of f] = sum over h in L*, h != 0, of |f^(h)|^2,
// a sum over isolated frequencies of density 1/N instead of over every
// integer frequency: exact, cheap, and the reason a generator can be chosen
// by the variance it gives.

// The nonzero dual points with |h| <= radius, one of each +-h pair (the sum
// is even in h for real f), in a fixed order. g must be coprime to N.
std::vector<Frequency> Rank1DualHalfDisk(uint32_t n, uint32_t g, int radius);

// The sum over the dual points 0 < |h| <= radius, and a corrected estimate of
// the whole sum. For an integrand with discontinuities |f^|^2 decays like
// 1/|h|^2 along lines, so the dual points beyond R carry about c / R; from
// the sums at R/2 and R, `extrapolated` = 2 S(R) - S(R/2) removes that term
// (checked against the Monte Carlo variance in the tests).
struct LatticeVariance {
  double head = 0.0;          // sum over 0 < |h| <= radius
  double half_radius = 0.0;   // the same sum to radius / 2
  double extrapolated = 0.0;  // 2 head - half_radius, never below head
  int radius = 0;
};
LatticeVariance Rank1CpVariance(uint32_t n, uint32_t g, const Integrand& f, int radius);

// |f^(h)|^2 of a convex polygon's indicator at a frequency h != 0, by the
// divergence theorem:
//   f^(h) = i / (2 pi |h|^2) sum over edges e of
//           (h_x e_y - h_y e_x) sinc(h . e) exp(-2 pi i h . m_e),
// e the edge vector, m_e its midpoint, vertices counter-clockwise. The
// indicator-only special case of LinearPolygonFourier (the tests hold one
// against the other), without its small-|h| branches: a generator search
// evaluates it at millions of dual points.
class IndicatorSpectrum {
 public:
  explicit IndicatorSpectrum(const Polygon& polygon);
  double Energy(double hx, double hy) const;

 private:
  struct Edge {
    double ex, ey, mx, my;
  };
  std::vector<Edge> edges_;
};

}  // namespace alignset

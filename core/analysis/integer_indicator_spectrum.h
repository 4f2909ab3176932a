#pragma once

#include <complex>
#include <cstddef>
#include <vector>

#include "core/analysis/convex_polygon.h"

namespace alignset {

// IndicatorSpectrum's |f^(h)|^2 (lattice_variance.h) at integer frequencies,
// without a sine or cosine per edge and frequency. A generator search
// evaluates it at millions of dual points, and there the trigonometry was
// 80% of `alignset render`'s time at N = 1024. Per edge from a to b,
//   sinc(h . e) exp(-2 pi i h . m) = (E(a) - E(b)) / (2 pi i h . e),
// E(p) = exp(-2 pi i h . p), so only the vertices' exponentials are needed,
// and E(p) = X_p(h_x) Y_p(h_y) splits into two tables over the integers.
// For integer h a vertex on the unit square's sides has a trivial factor
// (exp(-2 pi i k) = 1 for x or y in {0, 1}), so a square clipped by a
// half-plane (the scored edges) needs two small one-dimensional tables.
// Vertices off the sides (a polygon scaled into a quadrant of the square, as
// the tent-folded edges are) have tables of their own.
// Where h . e is near zero the difference cancels; there the factor is
// E(a) (1 - exp(-2 pi i u)) / (2 pi i u) by its Taylor series.
class IntegerIndicatorSpectrum {
 public:
  // At most this many vertices (a clipped square has five).
  static constexpr size_t kMaxVertices = 16;
  // Tables for |h_x| <= radius and 0 <= h_y <= radius; beyond them, or with
  // tabulate = false (a caller short of memory), the vertices' factors are
  // computed on the spot, two sines and cosines per vertex off the square's
  // sides instead of two per edge.
  IntegerIndicatorSpectrum(const Polygon& polygon, int radius, bool tabulate = true);
  // False for a polygon of more than kMaxVertices vertices, whose energy
  // is then 0.
  bool Valid() const { return !vertices_.empty(); }
  // h != 0.
  double Energy(int hx, int hy) const;
  // The edge sum S(h) of the divergence theorem, f^(h) = i S(h) / (2 pi |h|^2)
  // (lattice_variance.h's IndicatorSpectrum): the coefficients of a union of
  // disjoint polygons add, and so do their sums. h != 0.
  std::complex<double> Sum(int hx, int hy) const;
  // The bytes its tables hold.
  size_t TableBytes() const;

 private:
  using Complex = std::complex<double>;
  struct Vertex {
    double x = 0.0, y = 0.0;
    bool x_trivial = false, y_trivial = false;  // on x in {0, 1} or y in {0, 1}
    std::vector<Complex> xs, ys;                // xs[h_x + radius], ys[h_y]
  };
  struct Edge {
    size_t a = 0, b = 0;  // vertices
    double ex = 0.0, ey = 0.0;
  };
  Complex Exponential(const Vertex& v, int hx, int hy) const;

  int radius_ = 0;
  std::vector<Vertex> vertices_;
  std::vector<Edge> edges_;
};

// The energy |f^(h)|^2 of the indicator of a union of polygons with disjoint
// interiors, symmetric under the point reflection u -> (1, 1) - u, given by
// the spectra of one half's polygons (half[0 .. count)): the other half's
// coefficients are their conjugates, so f^(h) = 2 Re(sum of the half's
// f^(h)) = -2 Im(sum of their Sums) / (2 pi |h|^2). h != 0.
double SymmetricUnionEnergy(const IntegerIndicatorSpectrum* half, size_t count, int hx, int hy);

}  // namespace alignset

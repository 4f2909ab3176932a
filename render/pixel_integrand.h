#pragma once

#include <vector>

#include "render/geometry.h"

namespace alignset::render {

// One piece of a pixel's integrand: a convex polygon in the pixel's unit
// square with the linear function that holds inside it.
struct Fragment {
  Polygon polygon;
  Linear shade;
  Box box;
};

// A discontinuity of the integrand inside the pixel: a piece of a fragment's
// edge across which the value jumps. `normal_deg` is the edge's normal in
// [0, 180) (the spectral direction the aligned sets take).
struct EdgePiece {
  V2 a, b;
  double length = 0.0;
  double jump = 0.0;  // mean |value inside - value outside| along the piece
  double normal_deg = 0.0;
};

// What a pixel's integrand is made of.
enum class PixelClass {
  kEdge,      // at least one discontinuity of weight (length x jump) >= kEdgeWeight
  kSmooth,    // no discontinuity, but not constant (a linear gradient)
  kConstant,  // constant, or only negligible discontinuities: every sampler is exact or nearly
};
inline constexpr double kEdgeWeight = 1e-3;

// A pixel's integrand over its footprint, in local coordinates u in [0,1)^2:
// piecewise linear, the pieces disjoint convex fragments and the rest the
// background. Every scene reduces a pixel to this, so that point samples,
// line and segment samples and the exact reference all see one function.
class PixelIntegrand {
 public:
  PixelIntegrand() = default;
  PixelIntegrand(Linear background, std::vector<Fragment> fragments);

  double Eval(V2 u) const {
    for (const Fragment& f : fragments_) {
      if (u.x >= f.box.x0 && u.x <= f.box.x1 && u.y >= f.box.y0 && u.y <= f.box.y1 &&
          Contains(f.polygon, u)) {
        return f.shade(u);
      }
    }
    return background_(u);
  }
  // The value of a periodic repetition of the pixel (segment samples wrap).
  double EvalWrapped(V2 u) const;

  // The exact integral over [0,1]^2 (closed form per fragment).
  double Exact() const { return exact_; }

  // The exact integral of f along the segment a -> b, which must lie in
  // [0,1]^2 (arc-length measure).
  double LineIntegral(V2 a, V2 b) const;

  // The discontinuities inside the pixel (the pixel's own boundary is not
  // one). Shared edges are reported once; edges between pieces of one shape
  // with the same shade have no jump and are not reported.
  std::vector<EdgePiece> Discontinuities() const;
  PixelClass Classify() const;

  const Linear& background() const { return background_; }
  const std::vector<Fragment>& fragments() const { return fragments_; }

 private:
  // Which fragment holds u (-1: the background).
  int Owner(V2 u) const;

  Linear background_;
  std::vector<Fragment> fragments_;
  double exact_ = 0.0;
};

// Flattens an ordered list of convex polygons (front first) with their shades
// into disjoint fragments: each polygon minus everything in front of it.
// Occlusion is therefore exact: the reference needs no sampling.
struct ShadedPolygon {
  Polygon polygon;
  Linear shade;
};
std::vector<Fragment> Flatten(const std::vector<ShadedPolygon>& front_to_back, double min_area);

}  // namespace alignset::render

#pragma once

// Which aligned set a pixel reads, from its dominant directions: the step of
// the per-pixel recipe that a renderer shares with the server's key space.
// Used by the sampler library (<alignset/aligned_sampler.h>) and the project's
// renderer (render/). Header-only.

#include <alignset/directions.h>

#include <algorithm>

namespace alignset {

// What a pixel without a dominant direction gets, and whether pixels with
// two get a two-direction (4-direction) set.
struct AlignedPolicy {
  enum class None { kOwenSobol, kAxisSet };
  None none = None::kOwenSobol;
  bool two_directions = true;
};

// A pixel's dominant directions in degrees: `count` of them (0, 1 or 2),
// theta1 the stronger.
struct PixelDirections {
  int count = 0;
  double theta1_deg = 0.0;
  double theta2_deg = 0.0;
};

// The set a pixel gets, in served whole degrees.
//  - kFallback: no dominant direction and policy kOwenSobol (the renderer
//    samples the pixel with its own fallback, e.g. Owen-scrambled Sobol).
//  - kOne(a): one direction a; also a pixel whose second direction is an
//    axis (0 or 90 after rounding): every set already suppresses the axes,
//    so a 4-direction set would spend its strips twice. A pixel without a
//    dominant direction under kAxisSet gets kOne(0), the axis set.
//  - kTwo(a, b), a < b: two distinct non-axis directions.
struct SetChoice {
  enum class Kind { kFallback, kOne, kTwo };
  Kind kind = Kind::kFallback;
  int a = 0;
  int b = 0;
};

inline SetChoice ChooseSet(const PixelDirections& d, const AlignedPolicy& policy) {
  SetChoice c;
  auto is_axis = [](int deg) { return deg == 0 || deg == 90; };
  if (d.count == 0) {
    if (policy.none == AlignedPolicy::None::kAxisSet) {
      c.kind = SetChoice::Kind::kOne;
      c.a = 0;
    }
    return c;
  }
  const int a = ServedDegree(d.theta1_deg);
  c.kind = SetChoice::Kind::kOne;
  c.a = a;
  if (d.count != 2 || !policy.two_directions) return c;
  const int b = ServedDegree(d.theta2_deg);
  if (b == a || is_axis(b)) return c;
  if (is_axis(a)) {
    c.a = b;
    return c;
  }
  c.kind = SetChoice::Kind::kTwo;
  c.a = std::min(a, b);
  c.b = std::max(a, b);
  return c;
}

}  // namespace alignset

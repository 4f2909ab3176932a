#pragma once

#include <string>

#include "render/pixel_integrand.h"

namespace alignset::render {

// What an edge pixel's discontinuities look like, from the geometry: the
// pixel types the error of the aligned samplers is split by (issue 26).
//  - kStraight: one straight edge (every piece on one line);
//  - kParallel: pieces of one direction on two or more lines, a thin
//    feature (a bar narrower than the pixel, two parallel edges);
//  - kCurved:   several directions, all within kCurvedSpreadDeg of the
//    heaviest (a polygonized curve, a shallow corner);
//  - kCorner:   a second direction further away (a corner, a crossing).
// Pieces below kNegligibleShare of the pixel's edge weight (length x jump)
// are left out, as are non-edge pixels (kNone).
enum class PixelShape { kNone, kStraight, kParallel, kCurved, kCorner };
inline constexpr double kCurvedSpreadDeg = 15.0;
inline constexpr double kNegligibleShare = 0.01;

PixelShape ClassifyShape(const PixelIntegrand& f);
std::string ShapeName(PixelShape s);

}  // namespace alignset::render

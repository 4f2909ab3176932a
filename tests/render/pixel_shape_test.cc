// The pixel types the render error is split by (render/pixel_shape.h), on
// pixels built by hand and on the scenes.
#include "render/pixel_shape.h"

#include <gtest/gtest.h>

#include <cmath>
#include <map>

#include "render/scene.h"

namespace alignset::render {
namespace {

const Polygon kSquare = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};

V2 Normal(double deg) { return {std::cos(deg * M_PI / 180.0), std::sin(deg * M_PI / 180.0)}; }

// The part of the pixel on the positive side of the line with normal `deg`
// through `at`.
Polygon Half(const Polygon& p, double deg, V2 at) { return ClipHalfPlane(p, -1.0 * Normal(deg), -Dot(Normal(deg), at)); }

TEST(PixelShape, HandBuiltPixels) {
  const PixelIntegrand straight(Linear{0.2, 0, 0}, {Fragment{Half(kSquare, 30, {0.5, 0.5}), Linear{0.9, 0, 0}, {}}});
  EXPECT_EQ(ClassifyShape(straight), PixelShape::kStraight);
  // A bar 0.2 wide: two parallel edges.
  const Polygon bar = Half(Half(kSquare, 30, {0.4, 0.4}), 210, {0.6, 0.6});
  EXPECT_EQ(ClassifyShape(PixelIntegrand(Linear{0, 0, 0}, {Fragment{bar, Linear{1, 0, 0}, {}}})),
            PixelShape::kParallel);
  // A shallow bend (8°) and a corner (90°).
  const Polygon bend = Half(Half(kSquare, 30, {0.5, 0.5}), 38, {0.5, 0.5});
  EXPECT_EQ(ClassifyShape(PixelIntegrand(Linear{0, 0, 0}, {Fragment{bend, Linear{1, 0, 0}, {}}})),
            PixelShape::kCurved);
  const Polygon wedge = Half(Half(kSquare, 30, {0.5, 0.5}), 120, {0.5, 0.5});
  EXPECT_EQ(ClassifyShape(PixelIntegrand(Linear{0, 0, 0}, {Fragment{wedge, Linear{1, 0, 0}, {}}})),
            PixelShape::kCorner);
  // Not an edge pixel.
  EXPECT_EQ(ClassifyShape(PixelIntegrand(Linear{1, 0.1, 0}, {})), PixelShape::kNone);
  // One edge cut into two pieces of one shade is still one straight edge.
  const Polygon half = Half(kSquare, 30, {0.5, 0.5});
  const Polygon lo = ClipHalfPlane(half, {0, 1}, 0.3), hi = ClipHalfPlane(half, {0, -1}, -0.3);
  EXPECT_EQ(ClassifyShape(PixelIntegrand(Linear{0.2, 0, 0}, {Fragment{lo, Linear{0.9, 0, 0}, {}},
                                                              Fragment{hi, Linear{0.9, 0, 0}, {}}})),
            PixelShape::kStraight);
}

TEST(PixelShape, EveryEdgePixelOfTheScenesHasOneTypeAndTheAntialiasSceneHasAllFour) {
  for (const char* name : {"antialias", "shadow"}) {
    const Scene scene = *MakeScene(name, 128, 128, 1);
    const std::vector<PixelClass> classes = scene.Classes();
    std::map<PixelShape, int> count;
    for (size_t i = 0; i < scene.size(); ++i) {
      const PixelShape s = ClassifyShape(scene.Pixel(i));
      EXPECT_EQ(s == PixelShape::kNone, classes[i] != PixelClass::kEdge) << name << " pixel " << i;
      ++count[s];
    }
    EXPECT_GT(count[PixelShape::kStraight], count[PixelShape::kCorner]) << name;
    if (std::string(name) == "antialias") {
      for (PixelShape s : {PixelShape::kStraight, PixelShape::kParallel, PixelShape::kCurved, PixelShape::kCorner}) {
        EXPECT_GT(count[s], 10) << ShapeName(s);
      }
    }
  }
}

}  // namespace
}  // namespace alignset::render

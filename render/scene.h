#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "render/pixel_integrand.h"
#include "core/util/status.h"

namespace alignset::render {

// How neighbouring pixels' integration domains lie to each other, which is
// what a renderer knows about its integral without knowing the geometry:
// kFootprint, each pixel's [0,1)^2 is its square in the image plane, beside
// its neighbours' (an edge runs on into the next pixel); kShared, every
// pixel integrates over the same square (an area light seen from each
// receiver point: the neighbours see the same edges, moved a little).
enum class PixelDomain { kFootprint, kShared };

// A W x H image whose every pixel is a 2-D integrand over [0,1)^2 with an
// exact integral. Pixel (x, y) is row y, column x; images are stored row by
// row (index y * W + x), y growing upwards in the scene's own coordinates.
class Scene {
 public:
  Scene() = default;
  Scene(std::string name, int width, int height, std::vector<PixelIntegrand> pixels,
        PixelDomain domain = PixelDomain::kFootprint);

  const std::string& name() const { return name_; }
  int width() const { return width_; }
  int height() const { return height_; }
  size_t size() const { return pixels_.size(); }
  const PixelIntegrand& Pixel(int x, int y) const { return pixels_[y * width_ + x]; }
  const PixelIntegrand& Pixel(size_t index) const { return pixels_[index]; }
  PixelDomain domain() const { return domain_; }

  // The exact image: every pixel's closed-form integral.
  std::vector<double> Reference() const;
  std::vector<PixelClass> Classes() const;

 private:
  std::string name_;
  int width_ = 0, height_ = 0;
  std::vector<PixelIntegrand> pixels_;
  PixelDomain domain_ = PixelDomain::kFootprint;
};

// (a) Antialiasing of a vector scene: triangles, thin bars, a star and a
// many-sided curved blob at random orientations over a gradient background,
// some flat and some with linear gradients, in front-to-back order. A pixel's
// value is the integral over its square footprint.
Scene MakeAntialiasScene(int width, int height, uint64_t seed);

// (b) Soft shadows: a square area light above a receiver plane, polygonal
// occluders (planks, some tilted, triangles, a star) between them. A receiver
// pixel's integrand over the light's [0,1)^2 is the visibility of the light
// point times a linear emission profile; projected occluders are unioned
// exactly.
Scene MakeShadowScene(int width, int height, uint64_t seed);

// The 3-D description behind MakeShadowScene (tests cast rays against it
// to check the projected references independently).
struct V3 {
  double x = 0.0, y = 0.0, z = 0.0;
};
struct ShadowGeometry {
  double light_height = 3.0;
  double light_side = 0.6;
  V2 light_corner;              // the light spans corner + side * [0,1]^2 at light_height
  double receiver_size = 8.0;   // the image covers [0, size]^2 of the plane z = 0
  Linear emission;              // over the light's [0,1)^2
  std::vector<std::vector<V3>> occluders;  // planar convex pieces, 0 < z < light_height
  V3 ReceiverPoint(int x, int y, int width, int height) const {
    return {(x + 0.5) * receiver_size / width, (y + 0.5) * receiver_size / height, 0.0};
  }
  V3 LightPoint(V2 u) const {
    return {light_corner.x + light_side * u.x, light_corner.y + light_side * u.y, light_height};
  }
};
ShadowGeometry MakeShadowGeometry(uint64_t seed);

// "antialias" or "shadow"; INVALID_ARGUMENT for anything else or a size
// outside [1, 4096].
StatusOr<Scene> MakeScene(const std::string& name, int width, int height, uint64_t seed);
std::vector<std::string> SceneNames();

}  // namespace alignset::render

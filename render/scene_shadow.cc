// Scene (b): soft shadows. A square light of side light_side at height
// light_height over the receiver plane z = 0; planar convex occluder pieces
// (3-D vertices, some in tilted planes) in between. From a receiver point p
// an occluder vertex q projects onto the light's plane at
// p + (q - p) * light_height / q.z; a central projection maps a planar convex
// polygon to a convex polygon, so the blocked part of the light is a union of
// convex polygons, made disjoint by Flatten and integrated exactly. Tilted
// occluders make the projected edges turn across the image.

#include <algorithm>
#include <cmath>

#include "render/scene.h"
#include "core/util/angles.h"
#include "core/util/hash.h"

namespace alignset::render {

ShadowGeometry MakeShadowGeometry(uint64_t seed) {
  Pcg32 rng(HashCombine(seed, 0x5AD0ULL));
  ShadowGeometry g;
  g.light_height = 3.0;
  g.light_side = 0.6;
  g.receiver_size = 8.0;
  g.light_corner = {4.0 - 0.5 * g.light_side + 0.3, 4.0 - 0.5 * g.light_side - 0.2};
  // The emission profile over the light's [0,1)^2: linear, brighter towards +x.
  g.emission = Linear{1.0 - 0.35 * 0.5 + 0.25 * 0.5, 0.35, -0.25};
  std::vector<std::vector<V3>>& pieces = g.occluders;  // convex, planar

  // Planks, half of them tilted along their length.
  for (int i = 0; i < 6; ++i) {
    const double cx = 1.5 + 5.0 * rng.NextDouble(), cy = 1.5 + 5.0 * rng.NextDouble();
    const double z0 = 0.8 + 0.6 * rng.NextDouble();
    const double len = 2.5 + 2.5 * rng.NextDouble(), wid = 0.2 + 0.4 * rng.NextDouble();
    const double a = kPi * rng.NextDouble();
    const double dz = i % 2 ? 0.0 : 0.35 * (2.0 * rng.NextDouble() - 1.0);  // z change end to end / 2
    const V2 d = {std::cos(a), std::sin(a)}, e = {-d.y, d.x};
    std::vector<V3> p;
    for (V2 k : {V2{-0.5, -0.5}, V2{0.5, -0.5}, V2{0.5, 0.5}, V2{-0.5, 0.5}}) {
      p.push_back({cx + k.x * len * d.x + k.y * wid * e.x, cy + k.x * len * d.y + k.y * wid * e.y,
                   z0 + 2.0 * k.x * dz});
    }
    pieces.push_back(p);
  }
  // Triangles, some tilted (a plane z = z0 + g.(x - c)).
  for (int i = 0; i < 3; ++i) {
    const double cx = 1.5 + 5.0 * rng.NextDouble(), cy = 1.5 + 5.0 * rng.NextDouble();
    const double z0 = 0.8 + 0.6 * rng.NextDouble(), r = 0.5 + 0.5 * rng.NextDouble();
    const double gx = 0.3 * (2 * rng.NextDouble() - 1), gy = 0.3 * (2 * rng.NextDouble() - 1);
    const double a0 = 2 * kPi * rng.NextDouble();
    std::vector<V3> t;
    for (int k = 0; k < 3; ++k) {
      const double a = a0 + k * 2 * kPi / 3 + 0.4 * (rng.NextDouble() - 0.5);
      const double x = cx + r * std::cos(a), y = cy + r * std::sin(a);
      t.push_back({x, y, z0 + gx * (x - cx) + gy * (y - cy)});
    }
    pieces.push_back(t);
  }
  // A flat five-pointed star, as a fan of triangles.
  {
    const double cx = 2.0 + 4.0 * rng.NextDouble(), cy = 2.0 + 4.0 * rng.NextDouble(), z = 1.2;
    const double a0 = 2 * kPi * rng.NextDouble();
    std::vector<V3> outline;
    for (int k = 0; k < 10; ++k) {
      const double r = k % 2 ? 0.4 : 0.9, a = a0 + k * kPi / 5;
      outline.push_back({cx + r * std::cos(a), cy + r * std::sin(a), z});
    }
    for (int k = 0; k < 10; ++k) pieces.push_back({{cx, cy, z}, outline[k], outline[(k + 1) % 10]});
  }

  return g;
}

Scene MakeShadowScene(int width, int height, uint64_t seed) {
  const ShadowGeometry g = MakeShadowGeometry(seed);
  std::vector<PixelIntegrand> pixels;
  pixels.reserve(static_cast<size_t>(width) * height);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const V3 p = g.ReceiverPoint(x, y, width, height);
      std::vector<ShadedPolygon> blocked;
      for (const std::vector<V3>& piece : g.occluders) {
        Polygon proj;
        for (const V3& q : piece) {
          const double t = g.light_height / q.z;
          const V2 hit = {p.x + (q.x - p.x) * t, p.y + (q.y - p.y) * t};
          proj.push_back((1.0 / g.light_side) * (hit - g.light_corner));
        }
        Polygon clipped = ClipRect(MakeCounterClockwise(proj), 0, 0, 1, 1);
        if (clipped.size() >= 3 && Area(clipped) > 1e-14) blocked.push_back({clipped, Linear{}});
      }
      pixels.emplace_back(g.emission, Flatten(blocked, 1e-14));
    }
  }
  return Scene("shadow", width, height, std::move(pixels), PixelDomain::kShared);
}

}  // namespace alignset::render

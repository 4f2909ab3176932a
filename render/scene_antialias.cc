// Scene (a): antialiasing a vector drawing. Built in image coordinates (one
// unit per pixel), flattened once into disjoint fragments (each shape minus
// the shapes in front of it), then cut into per-pixel integrands.

#include <algorithm>
#include <cmath>

#include "render/scene.h"
#include "core/util/angles.h"
#include "core/util/hash.h"

namespace alignset::render {
namespace {

struct Shape {
  std::vector<Polygon> pieces;  // convex, counter-clockwise
  Linear shade;
};

V2 Rotate(V2 v, double rad) {
  const double c = std::cos(rad), s = std::sin(rad);
  return {c * v.x - s * v.y, s * v.x + c * v.y};
}

// Flat with probability 1/2, otherwise a linear gradient that changes by
// about `swing` across `size` in a random direction.
Linear RandomShade(Pcg32& rng, V2 centre, double size) {
  const double v = 0.15 + 0.8 * rng.NextDouble();
  if (rng.NextDouble() < 0.5) return {v, 0.0, 0.0};
  const double dir = 2.0 * kPi * rng.NextDouble();
  const double m = (0.3 + 0.4 * rng.NextDouble()) / size;
  const double gx = m * std::cos(dir), gy = m * std::sin(dir);
  return {v - gx * centre.x - gy * centre.y, gx, gy};
}

// A polygon that is star-shaped about `centre`, as a fan of triangles.
std::vector<Polygon> Fan(V2 centre, const std::vector<V2>& outline) {
  std::vector<Polygon> fan;
  for (size_t i = 0, n = outline.size(); i < n; ++i) {
    fan.push_back(MakeCounterClockwise({centre, outline[i], outline[(i + 1) % n]}));
  }
  return fan;
}

V2 RandomCentre(Pcg32& rng, double w, double h, double margin) {
  return {margin + (w - 2 * margin) * rng.NextDouble(), margin + (h - 2 * margin) * rng.NextDouble()};
}

}  // namespace

Scene MakeAntialiasScene(int width, int height, uint64_t seed) {
  Pcg32 rng(HashCombine(seed, 0xa17a5ULL));
  const double w = width, h = height;
  const double s = std::min(w, h) / 128.0;
  std::vector<Shape> shapes;  // front first

  // Thin bars, 1-3 pixels wide, at uniformly random orientations.
  for (int i = 0; i < 10; ++i) {
    const V2 c = RandomCentre(rng, w, h, 10 * s);
    const double len = (30 + 40 * rng.NextDouble()) * s, bw = (1.0 + 2.0 * rng.NextDouble()) * s;
    const double a = kPi * rng.NextDouble();
    Polygon p;
    for (V2 corner : {V2{-0.5, -0.5}, V2{0.5, -0.5}, V2{0.5, 0.5}, V2{-0.5, 0.5}}) {
      p.push_back(c + Rotate({corner.x * len, corner.y * bw}, a));
    }
    shapes.push_back({{MakeCounterClockwise(p)}, RandomShade(rng, c, len)});
  }
  // A star with 5 to 7 points.
  {
    const V2 c = RandomCentre(rng, w, h, 24 * s);
    const int points = 5 + static_cast<int>(rng.Uniform(3));
    const double r_out = 20 * s, r_in = 9 * s, a0 = 2 * kPi * rng.NextDouble();
    std::vector<V2> outline;
    for (int k = 0; k < 2 * points; ++k) {
      const double r = k % 2 ? r_in : r_out;
      outline.push_back(c + Rotate({r, 0}, a0 + k * kPi / points));
    }
    shapes.push_back({Fan(c, outline), RandomShade(rng, c, 2 * r_out)});
  }
  // Triangles: random vertex angles around a centre, so that every edge
  // orientation occurs.
  for (int i = 0; i < 12; ++i) {
    const V2 c = RandomCentre(rng, w, h, 12 * s);
    const double r = (8 + 10 * rng.NextDouble()) * s;
    double angles[3];
    for (double& a : angles) a = 2 * kPi * rng.NextDouble();
    std::sort(angles, angles + 3);
    if (angles[1] - angles[0] < 0.6) angles[1] = angles[0] + 0.6;
    if (angles[2] - angles[1] < 0.6) angles[2] = angles[1] + 0.6;
    if (angles[0] + 2 * kPi - angles[2] < 0.6) angles[2] = angles[0] + 2 * kPi - 0.6;
    Polygon t;
    for (double a : angles) t.push_back(c + Rotate({r * (0.7 + 0.3 * rng.NextDouble()), 0}, a));
    shapes.push_back({{MakeCounterClockwise(t)}, RandomShade(rng, c, 2 * r)});
  }
  // A curved-looking blob: 64 sides, radius varying smoothly with the angle.
  {
    const V2 c = RandomCentre(rng, w, h, 30 * s);
    const double r = 24 * s, p0 = 2 * kPi * rng.NextDouble(), p1 = 2 * kPi * rng.NextDouble();
    std::vector<V2> outline;
    for (int k = 0; k < 64; ++k) {
      const double a = 2 * kPi * k / 64;
      const double rk = r * (1 + 0.18 * std::sin(3 * a + p0) + 0.08 * std::sin(5 * a + p1));
      outline.push_back(c + Rotate({rk, 0}, a));
    }
    shapes.push_back({Fan(c, outline), RandomShade(rng, c, 2 * r)});
  }

  std::vector<ShadedPolygon> ordered;
  for (const Shape& shape : shapes) {
    for (const Polygon& p : shape.pieces) ordered.push_back({p, shape.shade});
  }
  const std::vector<Fragment> fragments = Flatten(ordered, 1e-12);
  const Linear background{0.35, 0.25 / w, 0.15 / h};

  // Cut into pixels: each fragment clipped to every pixel its bounds touch.
  std::vector<std::vector<Fragment>> per_pixel(static_cast<size_t>(width) * height);
  for (const Fragment& f : fragments) {
    const int x0 = std::max(0, static_cast<int>(std::floor(f.box.x0)));
    const int x1 = std::min(width - 1, static_cast<int>(std::floor(f.box.x1)));
    const int y0 = std::max(0, static_cast<int>(std::floor(f.box.y0)));
    const int y1 = std::min(height - 1, static_cast<int>(std::floor(f.box.y1)));
    for (int y = y0; y <= y1; ++y) {
      for (int x = x0; x <= x1; ++x) {
        Polygon clipped = ClipRect(f.polygon, x, y, x + 1, y + 1);
        if (clipped.size() < 3 || Area(clipped) < 1e-14) continue;
        for (V2& q : clipped) q = q - V2{double(x), double(y)};
        Fragment local;
        local.polygon = std::move(clipped);
        local.shade = f.shade.InLocal({double(x), double(y)}, 1.0);
        per_pixel[static_cast<size_t>(y) * width + x].push_back(std::move(local));
      }
    }
  }
  std::vector<PixelIntegrand> pixels;
  pixels.reserve(per_pixel.size());
  for (size_t i = 0; i < per_pixel.size(); ++i) {
    const int x = static_cast<int>(i % width), y = static_cast<int>(i / width);
    pixels.emplace_back(background.InLocal({double(x), double(y)}, 1.0), std::move(per_pixel[i]));
  }
  return Scene("antialias", width, height, std::move(pixels));
}

}  // namespace alignset::render

// A renderer of its own, built against the installed package only: a
// triangle's silhouette on a 32 x 32 image, its edge pixels rendered through
// the sampler library with a table file (no server), against Owen-scrambled
// Sobol at the same total samples. Owen-Sobol and the exact coverage are
// written here from scratch, sharing no code with alignset.
//   render_with_table TABLE.tbl
#include <alignset/aligned_sampler.h>
#include <alignset/set_table.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <vector>

namespace {

constexpr uint32_t kSize = 32, kN = 256;
struct V {
  double x, y;
};
// The triangle, in pixels: edges at angles nobody tuned on.
const V kTri[3] = {{3.3, 4.1}, {28.7, 9.6}, {11.2, 27.9}};

bool Inside(double x, double y) {
  for (int i = 0; i < 3; ++i) {
    const V a = kTri[i], b = kTri[(i + 1) % 3];
    if ((b.x - a.x) * (y - a.y) - (b.y - a.y) * (x - a.x) < 0) return false;
  }
  return true;
}

// The exact area of the triangle inside pixel (px, py): the pixel square
// clipped by the triangle's three half-planes.
double Coverage(uint32_t px, uint32_t py) {
  std::vector<V> poly = {{px + 0.0, py + 0.0}, {px + 1.0, py + 0.0}, {px + 1.0, py + 1.0}, {px + 0.0, py + 1.0}};
  for (int i = 0; i < 3; ++i) {
    const V a = kTri[i], b = kTri[(i + 1) % 3];
    auto side = [&](V p) { return (b.x - a.x) * (p.y - a.y) - (b.y - a.y) * (p.x - a.x); };
    std::vector<V> out;
    for (size_t k = 0; k < poly.size(); ++k) {
      const V p = poly[k], q = poly[(k + 1) % poly.size()];
      const double sp = side(p), sq = side(q);
      if (sp >= 0) out.push_back(p);
      if ((sp >= 0) != (sq >= 0)) out.push_back({p.x + sp / (sp - sq) * (q.x - p.x), p.y + sp / (sp - sq) * (q.y - p.y)});
    }
    poly = out;
  }
  double area = 0;
  for (size_t k = 0; k < poly.size(); ++k) area += poly[k].x * poly[(k + 1) % poly.size()].y - poly[(k + 1) % poly.size()].x * poly[k].y;
  return 0.5 * std::fabs(area);
}

// Owen-scrambled Sobol, two dimensions, Burley's hash-based nested scramble.
uint32_t Reverse(uint32_t v) {
  uint32_t r = 0;
  for (int i = 0; i < 32; ++i, v >>= 1) r = (r << 1) | (v & 1);
  return r;
}
uint32_t Scramble(uint32_t v, uint32_t seed) {
  v = Reverse(v);
  v += seed;
  v ^= v * 0x6c50b47cu;
  v ^= v * 0xb82f1e52u;
  v ^= v * 0xc7afe638u;
  v ^= v * 0x8d22f6e6u;
  return Reverse(v);
}
double OwenSobolMean(uint32_t px, uint32_t py, uint32_t count, uint32_t seed) {
  double sum = 0;
  for (uint32_t i = 0; i < count; ++i) {
    const uint32_t j = Scramble(i, seed * 3 + 1);
    uint32_t d1 = 0, v = 1u << 31;
    for (uint32_t bits = j; bits; bits >>= 1, v ^= v >> 1) d1 ^= (bits & 1) ? v : 0;
    const double u = Scramble(Reverse(j), seed * 3 + 2) * 0x1p-32;
    const double w = Scramble(d1, seed * 3 + 3) * 0x1p-32;
    sum += Inside(px + u, py + w);
  }
  return sum / count;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) return std::fprintf(stderr, "usage: render_with_table TABLE\n"), 2;
  // 1. The table, loaded once; 2. one sampler for the render.
  auto table = alignset::SetTable::Load(argv[1]);
  if (!table.ok()) return std::fprintf(stderr, "%s\n", table.status().message().c_str()), 1;
  alignset::AlignedSamplerOptions options;
  options.n = kN;
  options.construction = "lattice";
  options.domain = alignset::PixelDomain::kFootprint;  // pixels are squares of the image plane
  options.image_width = kSize;
  auto sampler = alignset::AlignedSampler::Create(*table, options);
  if (!sampler.ok()) return std::fprintf(stderr, "%s\n", sampler.status().message().c_str()), 1;
  const uint32_t m = sampler->prepass_samples();
  const int r = sampler->block_radius(), side = sampler->block_side();

  // 3. The pre-pass of every pixel (a tiled renderer: a tile and its apron).
  std::vector<std::vector<double>> pre(kSize * kSize);
  std::vector<alignset::Point2> points(std::max(m, kN));
  for (uint32_t y = 0; y < kSize; ++y) {
    for (uint32_t x = 0; x < kSize; ++x) {
      sampler->PrepassPoints(x, y, std::span(points).first(m));
      for (uint32_t j = 0; j < m; ++j) pre[y * kSize + x].push_back(Inside(x + points[j].x, y + points[j].y));
    }
  }
  // 4. Each pixel: plan from its block, main points, estimate.
  alignset::AlignedSampler::Scratch scratch;  // one per thread
  std::vector<std::span<const double>> block(side * side);
  double ours = 0, theirs = 0;
  int edge_pixels = 0;
  for (uint32_t y = 0; y < kSize; ++y) {
    for (uint32_t x = 0; x < kSize; ++x) {
      for (int k = 0; k < side * side; ++k) {
        const int bx = int(x) + k % side - r, by = int(y) + k / side - r;
        const bool in = bx >= 0 && by >= 0 && bx < int(kSize) && by < int(kSize);
        block[k] = in ? std::span<const double>(pre[by * kSize + bx]) : std::span<const double>();
      }
      auto plan = sampler->Plan(x, y, block, scratch);
      if (!plan.ok()) return std::fprintf(stderr, "%s\n", plan.status().message().c_str()), 1;
      sampler->MainPoints(*plan, std::span(points).first(kN));
      std::vector<double> main;
      for (uint32_t i = 0; i < kN; ++i) main.push_back(Inside(x + points[i].x, y + points[i].y));
      const double estimate = sampler->Estimate(*plan, pre[y * kSize + x], main);
      // Edge pixels, classified from the geometry alone.
      const double exact = Coverage(x, y);
      if (exact <= 0.02 || exact >= 0.98) continue;
      const double owen = OwenSobolMean(x, y, m + kN, y * kSize + x);  // every sample counted
      ours += (estimate - exact) * (estimate - exact);
      theirs += (owen - exact) * (owen - exact);
      ++edge_pixels;
    }
  }
  std::printf("edge pixels %d: MSE aligned %.3g (%u + %u samples), Owen-Sobol %.3g (%u), ratio %.2f\n", edge_pixels,
              ours / edge_pixels, m, kN, theirs / edge_pixels, m + kN, theirs / ours);
  if (edge_pixels < 40 || !(theirs / ours > 1.5)) {
    std::fprintf(stderr, "render_with_table: the aligned sampler did not beat Owen-Sobol on edge pixels\n");
    return 1;
  }
  return 0;
}

#include "core/sampling/screen_space_rank1.h"

#include <algorithm>
#include <cmath>

#include "core/sampling/periodic_blur.h"
#include "core/sampling/rank1_lattice.h"
#include "core/util/angles.h"
#include "core/util/hash.h"

namespace alignset {
namespace {

// A Heaviside test integrand: 1 where (p - c).n >= 0.
struct HalfPlane {
  double nx, ny, c;  // n.p >= c
  double area;       // exact integral over [0,1]^2
};

// Area of {p in [0,1]^2 : n.p >= c}: the unit square clipped by one line
// (Sutherland-Hodgman), then the shoelace formula.
double ClippedSquareArea(double nx, double ny, double c) {
  const double sq[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  double poly[8][2];
  int m = 0;
  for (int i = 0; i < 4; ++i) {
    const double* a = sq[i];
    const double* b = sq[(i + 1) % 4];
    const double da = nx * a[0] + ny * a[1] - c, db = nx * b[0] + ny * b[1] - c;
    if (da >= 0) {
      poly[m][0] = a[0];
      poly[m][1] = a[1];
      ++m;
    }
    if ((da > 0 && db < 0) || (da < 0 && db > 0)) {
      const double t = da / (da - db);
      poly[m][0] = a[0] + t * (b[0] - a[0]);
      poly[m][1] = a[1] + t * (b[1] - a[1]);
      ++m;
    }
  }
  double area = 0.0;
  for (int i = 0; i < m; ++i) {
    area += poly[i][0] * poly[(i + 1) % m][1] - poly[(i + 1) % m][0] * poly[i][1];
  }
  return 0.5 * std::abs(area);
}

std::vector<HalfPlane> TestIntegrands(int count, uint64_t seed) {
  Pcg32 rng(HashCombine(seed, 0x7e57ULL));
  std::vector<HalfPlane> out(count);
  for (HalfPlane& h : out) {
    const double a = 2.0 * kPi * rng.NextDouble();
    h.nx = std::cos(a);
    h.ny = std::sin(a);
    const double px = rng.NextDouble(), py = rng.NextDouble();  // a point on the edge
    h.c = h.nx * px + h.ny * py;
    h.area = ClippedSquareArea(h.nx, h.ny, h.c);
  }
  return out;
}

// errors[p * T + t]: the error of the lattice shifted by tile.shifts[p] on
// integrand t.
std::vector<double> TileErrors(uint32_t n, const ShiftTile& tile,
                               const std::vector<HalfPlane>& integrands) {
  const uint32_t g = Rank1Generator(n);
  std::vector<double> bx(n), by(n);
  for (uint32_t k = 0; k < n; ++k) {
    bx[k] = static_cast<double>(k) / n;
    by[k] = static_cast<double>((static_cast<uint64_t>(k) * g) % n) / n;
  }
  const size_t pixels = tile.shifts.size(), t_count = integrands.size();
  std::vector<double> errors(pixels * t_count);
  std::vector<double> xs(n), ys(n);
  for (size_t p = 0; p < pixels; ++p) {
    const Point2 s = tile.shifts[p];
    for (uint32_t k = 0; k < n; ++k) {
      double x = bx[k] + s.x, y = by[k] + s.y;
      xs[k] = x >= 1.0 ? x - 1.0 : x;
      ys[k] = y >= 1.0 ? y - 1.0 : y;
    }
    for (size_t t = 0; t < t_count; ++t) {
      const HalfPlane& h = integrands[t];
      uint32_t inside = 0;
      for (uint32_t k = 0; k < n; ++k) inside += (h.nx * xs[k] + h.ny * ys[k] >= h.c);
      errors[p * t_count + t] = static_cast<double>(inside) / n - h.area;
    }
  }
  return errors;
}

}  // namespace

ScreenSpaceRank1::ScreenSpaceRank1(uint32_t n, ShiftTile tile)
    : n_(n), g_(Rank1Generator(n)), tile_(std::move(tile)) {}

PointSet ScreenSpaceRank1::PixelSet(int x, int y, Point2 extra) const {
  const Point2 s = tile_.At(x, y);
  const double sx = Wrap01(s.x + extra.x), sy = Wrap01(s.y + extra.y);
  PointSet out(n_);
  for (uint32_t k = 0; k < n_; ++k) {
    out[k] = {Wrap01(static_cast<double>(k) / n_ + sx),
              Wrap01(static_cast<double>((static_cast<uint64_t>(k) * g_) % n_) / n_ + sy)};
  }
  return out;
}

ShiftTile RandomShiftTile(int size, uint64_t seed) {
  Pcg32 rng(HashCombine(seed, 0x5417ULL));
  ShiftTile tile;
  tile.size = size;
  tile.shifts.resize(static_cast<size_t>(size) * size);
  for (Point2& s : tile.shifts) s = {rng.NextDouble(), rng.NextDouble()};
  return tile;
}

StatusOr<ShiftTile> OptimizeShiftTile(uint32_t n, const ShiftTileOptions& o,
                                      ShiftTileReport* report) {
  if (n < 1 || n > (1u << 20)) {
    return Status::InvalidArgument("screen-space rank-1: N must be in [1, 2^20], got " +
                                   std::to_string(n));
  }
  if (o.size < 2 || o.size > 256) {
    return Status::InvalidArgument("screen-space rank-1: tile size must be in [2, 256], got " +
                                   std::to_string(o.size));
  }
  if (o.test_integrands < 1) {
    return Status::InvalidArgument("screen-space rank-1: needs at least one test integrand");
  }
  const int size = o.size;
  const size_t pixels = static_cast<size_t>(size) * size;
  const size_t T = static_cast<size_t>(o.test_integrands);
  ShiftTile tile = RandomShiftTile(size, o.seed);
  const std::vector<HalfPlane> integrands = TestIntegrands(o.test_integrands, o.seed);
  std::vector<double> e = TileErrors(n, tile, integrands);

  // K = the autocorrelation of the blur; C_t = K * e_t (all t interleaved).
  const std::vector<double> k1 = RingAutocorrelation(PeriodicGaussianKernel(o.sigma, size));
  auto K = [&](int dx, int dy) {
    return k1[((dx % size) + size) % size] * k1[((dy % size) + size) % size];
  };
  // The offsets at which K can be nonzero, each residue mod `size` once
  // (the whole ring when the blur is as wide as the tile).
  int support = 0;
  for (int d = 0; d <= size / 2; ++d) {
    if (k1[d] != 0.0) support = d;
  }
  std::vector<int> offsets;
  if (2 * support + 1 <= size) {
    for (int o = -support; o <= support; ++o) offsets.push_back(o);
  } else {
    for (int o = 0; o < size; ++o) offsets.push_back(o);
  }
  std::vector<double> c(pixels * T, 0.0);
  // C_t(s) += w * v_t at every s = (cx, cy) + offset, w = sign * K(offset).
  auto scatter = [&](int cx, int cy, double sign, const double* v) {
    for (int oy : offsets) {
      for (int ox : offsets) {
        const double w = sign * K(ox, oy);
        if (w == 0.0) continue;
        const int sx = ((cx + ox) % size + size) % size, sy = ((cy + oy) % size + size) % size;
        double* cs = &c[(static_cast<size_t>(sy) * size + sx) * T];
        for (size_t t = 0; t < T; ++t) cs[t] += w * v[t];
      }
    }
  };
  for (size_t p = 0; p < pixels; ++p) {
    scatter(static_cast<int>(p % size), static_cast<int>(p / size), 1.0, &e[p * T]);
  }
  auto loss = [&] {
    double l = 0.0;
    for (size_t i = 0; i < pixels * T; ++i) l += e[i] * c[i];
    return l / static_cast<double>(pixels);
  };
  if (report) report->loss_before = loss();

  Pcg32 rng(HashCombine(o.seed, 0x5A9ULL));
  const int r = std::max(1, std::min(o.neighbourhood, size / 2));
  const uint64_t proposals = static_cast<uint64_t>(o.sweeps) * pixels;
  const double k0 = K(0, 0);
  std::vector<double> d(T);
  uint64_t accepted = 0;
  for (uint64_t i = 0; i < proposals; ++i) {
    const int px = static_cast<int>(rng.Uniform(size)), py = static_cast<int>(rng.Uniform(size));
    const int dx = static_cast<int>(rng.Uniform(2 * r + 1)) - r;
    const int dy = static_cast<int>(rng.Uniform(2 * r + 1)) - r;
    if (dx == 0 && dy == 0) continue;
    const int qx = ((px + dx) % size + size) % size, qy = ((py + dy) % size + size) % size;
    const size_t p = static_cast<size_t>(py) * size + px, q = static_cast<size_t>(qy) * size + qx;
    if (p == q) continue;
    const double kpq = K(px - qx, py - qy);
    double delta = 0.0;
    const double* ep = &e[p * T];
    const double* eq = &e[q * T];
    const double* cp = &c[p * T];
    const double* cq = &c[q * T];
    for (size_t t = 0; t < T; ++t) {
      d[t] = eq[t] - ep[t];
      delta += 2.0 * d[t] * (cp[t] - cq[t]) + 2.0 * d[t] * d[t] * (k0 - kpq);
    }
    if (!(delta < 0.0)) continue;
    ++accepted;
    std::swap(tile.shifts[p], tile.shifts[q]);
    for (size_t t = 0; t < T; ++t) std::swap(e[p * T + t], e[q * T + t]);
    // C_t(s) += d_t (K(s - p) - K(s - q)).
    scatter(px, py, 1.0, d.data());
    scatter(qx, qy, -1.0, d.data());
  }
  if (report) {
    report->loss_after = loss();
    report->proposals = proposals;
    report->accepted = accepted;
  }
  return tile;
}

std::vector<std::vector<double>> TileErrorMaps(uint32_t n, const ShiftTile& tile,
                                               int test_integrands, uint64_t seed) {
  const std::vector<HalfPlane> integrands = TestIntegrands(test_integrands, seed);
  const std::vector<double> e = TileErrors(n, tile, integrands);
  const size_t pixels = tile.shifts.size(), T = integrands.size();
  std::vector<std::vector<double>> maps(T, std::vector<double>(pixels));
  for (size_t t = 0; t < T; ++t) {
    for (size_t p = 0; p < pixels; ++p) maps[t][p] = e[p * T + t];
  }
  return maps;
}

double TileBlurCriterion(uint32_t n, const ShiftTile& tile, double sigma, int test_integrands,
                         uint64_t seed) {
  const std::vector<std::vector<double>> maps = TileErrorMaps(n, tile, test_integrands, seed);
  const size_t pixels = tile.shifts.size();
  double total = 0.0;
  for (const std::vector<double>& map : maps) {
    const std::vector<double> b = PeriodicGaussianBlur(map, tile.size, tile.size, sigma);
    double mean = 0.0, sq = 0.0;
    for (double v : b) {
      mean += v;
      sq += v * v;
    }
    mean /= pixels;
    total += sq / pixels - mean * mean;
  }
  return total / static_cast<double>(maps.size());
}

}  // namespace alignset

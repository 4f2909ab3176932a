#include "core/spectral/frequency_set.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>

#include "core/util/angles.h"

namespace alignset {
namespace {

struct TableRow {
  double n;
  double length, width, radius;
};
// Supplement, Table 1 (3 anisotropy directions).
constexpr std::array<TableRow, 5> kTable1 = {{
    {4096, 256, 5, 24},
    {8192, 384, 7, 32},
    {16384, 512, 9, 48},
    {32768, 768, 13, 56},
    {65536, 1024, 17, 64},
}};

// Slack for floating-point boundaries: a frequency exactly on a strip's edge
// belongs to the strip whatever the rounding of cos/sin.
constexpr double kEdgeEps = 1e-9;

bool IsCanonicalHalf(int a, int b) { return b > 0 || (b == 0 && a > 0); }

void AddStrip(const FrequencyParams& p, double deg, std::vector<Frequency>* out) {
  const Vec2 d = UnitVector(deg);
  const double half_w = 0.5 * p.width;
  const int ax = static_cast<int>(std::ceil(p.length * std::abs(d.x) + half_w * std::abs(d.y)));
  const int by = static_cast<int>(std::ceil(p.length * std::abs(d.y) + half_w * std::abs(d.x)));
  for (int b = 0; b <= by; ++b) {
    for (int a = -ax; a <= ax; ++a) {
      if (!IsCanonicalHalf(a, b)) continue;
      const double along = a * d.x + b * d.y;
      const double across = -a * d.y + b * d.x;
      if (std::abs(along) <= p.length + kEdgeEps && std::abs(across) <= half_w + kEdgeEps) {
        out->push_back({a, b});
      }
    }
  }
}

void AddDisk(const FrequencyParams& p, std::vector<Frequency>* out) {
  const int r = static_cast<int>(std::floor(p.radius + kEdgeEps));
  const double r2 = p.radius * p.radius + kEdgeEps;
  for (int b = 0; b <= r; ++b) {
    for (int a = -r; a <= r; ++a) {
      if (IsCanonicalHalf(a, b) && static_cast<double>(a) * a + static_cast<double>(b) * b <= r2) {
        out->push_back({a, b});
      }
    }
  }
}

void SortUnique(std::vector<Frequency>* k) {
  std::sort(k->begin(), k->end(), [](const Frequency& u, const Frequency& v) {
    return u.b != v.b ? u.b < v.b : u.a < v.a;
  });
  k->erase(std::unique(k->begin(), k->end()), k->end());
}

}  // namespace

FrequencyParams SupplementFrequencyParams(uint32_t n) {
  const double dn = std::max<double>(n, 1.0);
  FrequencyParams p;
  if (dn <= kTable1.front().n || dn >= kTable1.back().n) {
    const TableRow& row = dn <= kTable1.front().n ? kTable1.front() : kTable1.back();
    const double s = std::sqrt(dn / row.n);
    p = {row.length * s, row.width * s, row.radius * s};
  } else {
    size_t i = 0;
    while (kTable1[i + 1].n < dn) ++i;
    const TableRow& lo = kTable1[i];
    const TableRow& hi = kTable1[i + 1];
    const double t = std::log(dn / lo.n) / std::log(hi.n / lo.n);
    auto geo = [t](double a, double b) { return a * std::pow(b / a, t); };
    p = {geo(lo.length, hi.length), geo(lo.width, hi.width), geo(lo.radius, hi.radius)};
  }
  if (p.width < 1.0) {
    p.length *= p.width;  // keep length * width, i.e. the strip's count
    p.width = 1.0;
  }
  p.length = std::max(p.length, 1.0);
  p.radius = std::max(p.radius, 1.5);
  return p;
}

FrequencyParams DefaultFrequencyParams(uint32_t n) {
  FrequencyParams p = SupplementFrequencyParams(n);
  p.width *= kDefaultWidthScale;
  p.radius *= kDefaultRadiusScale;
  return p;
}

std::vector<double> AnisotropyDirections(const std::vector<double>& arbitrary) {
  std::vector<double> dirs = {0.0, 90.0};
  for (double d : arbitrary) dirs.push_back(ReduceDirection(d));
  return dirs;
}

Status ValidateFrequencyParams(const FrequencyParams& p) {
  for (double v : {p.length, p.width, p.radius}) {
    if (!std::isfinite(v) || v < 0.0) {
      return Status::InvalidArgument("frequency parameters must be finite and non-negative");
    }
  }
  // 2^14 keeps a strip's bounding box (and K) to a few hundred MB at most.
  if (p.length > 16384.0 || p.radius > 16384.0 || p.width > p.length * 2.0 + 2.0) {
    return Status::InvalidArgument("frequency parameters too large: length " +
                                   std::to_string(p.length) + ", width " +
                                   std::to_string(p.width) + ", radius " +
                                   std::to_string(p.radius));
  }
  return Status::Ok();
}

std::vector<Frequency> BuildFrequencySet(const FrequencyParams& params,
                                         const std::vector<double>& directions_deg) {
  std::vector<Frequency> k;
  AddDisk(params, &k);
  for (double deg : directions_deg) AddStrip(params, deg, &k);
  SortUnique(&k);
  return k;
}

std::vector<Frequency> StripFrequencies(const FrequencyParams& params, double direction_deg) {
  std::vector<Frequency> k;
  AddStrip(params, direction_deg, &k);
  SortUnique(&k);
  return k;
}

}  // namespace alignset

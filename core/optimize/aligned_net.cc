#include "core/optimize/aligned_net.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <string>

#include "core/analysis/convex_polygon.h"
#include "core/analysis/lattice_variance.h"
#include "core/sampling/owen_sobol.h"
#include "core/util/angles.h"
#include "core/util/hash.h"

namespace alignset {
namespace {

constexpr double kEdgeOffsets[] = {0.0, 0.21, -0.33};
constexpr int kWindowSteps = 2;  // 2 kWindowSteps + 1 normals per direction
// Around each direction's normal line, the frequencies within this many
// degrees beyond the window are weighed; every frequency below
// kLowRadiusFactor * sqrt(N) is.
constexpr double kWedgeMarginDeg = 10.0;
constexpr double kLowRadiusFactor = 2.0;

// The smooth guard: every frequency with |a|, |b| <= kSmoothBox is kept, and
// weighed by the coefficients of two smooth functions that are not periodic
// on the pixel (the corner term (x - 1/2)(y - 1/2), 1 / (4 pi^2 a b), and a
// centred Gaussian of sigma kSmoothSigma), so that the flips darken the edge
// without lighting the low frequencies a net keeps dark.
constexpr int kSmoothBox = 12;
constexpr double kSmoothSigma = 0.15;

struct Weighted {
  int a, b;
  double w;       // the edges' mean |f^|^2
  double smooth;  // the smooth guard's |f^|^2
};

double SmoothEnergy(int a, int b) {
  double e = std::exp(-4.0 * kPi * kPi * kSmoothSigma * kSmoothSigma * (double(a) * a + double(b) * b));
  if (a != 0 && b != 0) e += 1.0 / (16.0 * std::pow(kPi, 4) * double(a) * a * double(b) * b);
  return e;
}

std::vector<Weighted> Frequencies(uint32_t n, const std::vector<double>& dirs, const AlignedNetOptions& o) {
  std::vector<IndicatorSpectrum> edges;
  for (double d : dirs) {
    for (int k = -kWindowSteps; k <= kWindowSteps; ++k) {
      const Vec2 nn = UnitVector(d + o.window_deg * k / kWindowSteps);
      for (double offset : kEdgeOffsets) {
        Polygon p = ClipHalfPlane(UnitSquarePolygon(), nn, 0.5 * (nn.x + nn.y) + offset);
        if (SignedArea(p) > 1e-12) edges.emplace_back(p);
      }
    }
  }
  const double root = std::sqrt(static_cast<double>(n));
  const int radius = static_cast<int>(std::ceil(o.radius_factor * root));
  const double low = kLowRadiusFactor * root;
  const double wedge = (o.window_deg + kWedgeMarginDeg) * kPi / 180.0;
  std::vector<Weighted> out;
  for (int b = 1; b <= radius; ++b) {  // b > 0: one of each +-h; b = 0 and a = 0 are dark in a centred net
    for (int a = -radius; a <= radius; ++a) {
      if (a == 0) continue;
      const double r2 = double(a) * a + double(b) * b;
      if (r2 > double(radius) * radius) continue;
      bool keep = r2 <= low * low || (std::abs(a) <= kSmoothBox && b <= kSmoothBox);
      const double angle = std::atan2(double(b), double(a));  // (0, pi)
      for (double d : dirs) {
        const double t = ReduceDirection(d) * kPi / 180.0;
        double diff = std::fabs(angle - t);
        diff = std::min(diff, kPi - diff);
        keep |= diff <= wedge;
      }
      if (!keep) continue;
      double w = 0.0;
      for (const IndicatorSpectrum& e : edges) w += e.Energy(a, b);
      out.push_back({a, b, w / edges.size(), SmoothEnergy(a, b)});
    }
  }
  // The smooth guard's box first, then the heaviest edge frequencies.
  auto in_box = [](const Weighted& x) { return std::abs(x.a) <= kSmoothBox && x.b <= kSmoothBox; };
  std::stable_partition(out.begin(), out.end(), in_box);
  const size_t box = static_cast<size_t>(std::count_if(out.begin(), out.end(), in_box));
  const size_t k = std::min<size_t>(out.size(), std::max<size_t>(box, static_cast<size_t>(o.max_frequencies)));
  std::partial_sort(out.begin() + box, out.begin() + k, out.end(), [](const Weighted& x, const Weighted& y) {
    return x.w != y.w ? x.w > y.w : (x.a != y.a ? x.a < y.a : x.b < y.b);
  });
  out.resize(k);
  return out;
}

class FlipState {
 public:
  FlipState(uint32_t n, int m, uint64_t seed) : n_(n), m_(m) {
    for (int d = 0; d < 2; ++d) {
      out_[d].resize(n), pos_[d].resize(n);
      flips_[d].assign(n, 0);  // nodes 0 .. n-2
    }
    Pcg32 rng(seed);
    for (int d = 0; d < 2; ++d) {
      for (uint32_t i = 0; i + 1 < n; ++i) flips_[d][i] = rng.NextU32() & 1u;
    }
    // The first N Sobol points' m-digit coordinates are permutations of
    // 0 .. N-1 (the net): pos_ is their inverse, point i's input digits in
    // dimension d are the v with pos_[d][v] = i.
    for (uint32_t i = 0; i < n; ++i) {
      pos_[0][SobolDim0(i) >> (32 - m)] = i;
      pos_[1][SobolDim1(i) >> (32 - m)] = i;
    }
    for (int d = 0; d < 2; ++d) {
      for (uint32_t v = 0; v < n; ++v) out_[d][pos_[d][v]] = Scramble(d, v);
    }
  }
  static uint32_t Node(int level, uint32_t prefix) { return (1u << level) - 1 + prefix; }
  uint32_t Scramble(int d, uint32_t v) const {
    uint32_t r = 0;
    for (int k = 0; k < m_; ++k) {
      const uint32_t bit = (v >> (m_ - 1 - k)) & 1u;
      r = (r << 1) | (bit ^ flips_[d][Node(k, v >> (m_ - k))]);
    }
    return r;
  }
  double Coord(int d, uint32_t i) const { return (out_[d][i] + 0.5) / n_; }
  uint32_t Out(int d, uint32_t i) const { return out_[d][i]; }
  // The points under node (level, prefix) of dimension d.
  std::pair<const uint32_t*, uint32_t> Under(int d, int level, uint32_t prefix) const {
    const uint32_t size = n_ >> level;
    return {pos_[d].data() + prefix * size, size};
  }
  void Toggle(int d, int level, uint32_t prefix) {
    flips_[d][Node(level, prefix)] ^= 1u;
    const auto [idx, size] = Under(d, level, prefix);
    const uint32_t bit = 1u << (m_ - 1 - level);
    for (uint32_t k = 0; k < size; ++k) out_[d][idx[k]] ^= bit;
  }
  bool Bit(int d, uint32_t i, int level) const { return (out_[d][i] >> (m_ - 1 - level)) & 1u; }
  PointSet Points() const {
    PointSet p(n_);
    for (uint32_t i = 0; i < n_; ++i) p[i] = {Coord(0, i), Coord(1, i)};
    return p;
  }

 private:
  uint32_t n_;
  int m_;
  std::vector<uint32_t> out_[2], pos_[2];
  std::vector<uint32_t> flips_[2];
};

}  // namespace

StatusOr<AlignedNetResult> AlignedNet(uint32_t n, const std::vector<double>& directions_deg, uint64_t seed,
                                      const AlignedNetOptions& o) {
  if (n < 16 || n > 65536 || (n & (n - 1)) != 0) {
    return Status::InvalidArgument("an aligned net needs N a power of two in [16, 65536], got " +
                                   std::to_string(n));
  }
  if (directions_deg.empty() || directions_deg.size() > 8) {
    return Status::InvalidArgument("an aligned net takes 1 to 8 directions, got " +
                                   std::to_string(directions_deg.size()));
  }
  for (double d : directions_deg) {
    if (!std::isfinite(d)) return Status::InvalidArgument("direction must be finite");
  }
  if (!(o.window_deg >= 0.0 && o.window_deg <= 10.0) || !(o.radius_factor >= 1.0 && o.radius_factor <= 64.0) ||
      o.max_frequencies < 1 || o.max_frequencies > 1000000 || o.sweeps < 0 || o.sweeps > 100 ||
      !(o.smooth_weight >= 0.0 && o.smooth_weight <= 1000.0)) {
    return Status::InvalidArgument("aligned net options out of range");
  }
  int m = 0;
  while ((1u << m) < n) ++m;
  const std::vector<Weighted> freq = Frequencies(n, directions_deg, o);
  FlipState state(n, m, seed);
  // Every coordinate is (X + 1/2) / N with X an integer, so each phase
  // factor exp(-2 pi i h_d (2X + 1) / 2N) is a 2N-th root of unity: a table
  // instead of a sine and cosine per point and frequency.
  const uint32_t two_n = 2 * n;
  std::vector<std::complex<double>> root(two_n);
  for (uint32_t k = 0; k < two_n; ++k) {
    const double t = -2.0 * kPi * k / two_n;
    root[k] = {std::cos(t), std::sin(t)};
  }
  auto factor = [&](int h, uint32_t x) {
    const int64_t k = (static_cast<int64_t>(h) * (2 * static_cast<int64_t>(x) + 1)) % two_n;
    return root[static_cast<size_t>(k < 0 ? k + two_n : k)];
  };
  auto phase = [&](size_t f, uint32_t i) {
    return factor(freq[f].a, state.Out(0, i)) * factor(freq[f].b, state.Out(1, i));
  };

  // S(h) for every weighted frequency.
  const size_t kf = freq.size();
  std::vector<std::complex<double>> s(kf);
  std::vector<double> weight(kf, 0.0);
  auto objective = [&] {
    double j = 0.0;
    for (size_t f = 0; f < kf; ++f) j += weight[f] * std::norm(s[f]);
    return j;
  };
  for (size_t f = 0; f < kf; ++f) {
    std::complex<double> acc = 0.0;
    for (uint32_t i = 0; i < n; ++i) acc += phase(f, i);
    s[f] = acc;
  }
  AlignedNetResult r;
  r.frequencies = static_cast<int>(kf);
  // One weight per frequency: the edges' variance and the smooth guard's,
  // each relative to the random scramble's, the guard at smooth_weight.
  {
    double je = 0.0, js = 0.0;
    for (size_t f = 0; f < kf; ++f) je += freq[f].w * std::norm(s[f]), js += freq[f].smooth * std::norm(s[f]);
    for (size_t f = 0; f < kf; ++f) {
      weight[f] = freq[f].w / std::max(je, 1e-300) + o.smooth_weight * freq[f].smooth / std::max(js, 1e-300);
    }
  }
  r.start_objective = objective();

  std::vector<std::complex<double>> delta(kf);
  for (int sweep = 0; sweep < o.sweeps; ++sweep) {
    int accepted = 0;
    for (int level = 0; level < m; ++level) {
      const double step = std::ldexp(1.0, m - 1 - level) / n;  // the digit's weight
      for (int d = 0; d < 2; ++d) {
        for (uint32_t prefix = 0; prefix < (1u << level); ++prefix) {
          const auto [idx, size] = state.Under(d, level, prefix);
          double change = 0.0;
          for (size_t f = 0; f < kf; ++f) {
            const double hd = d == 0 ? freq[f].a : freq[f].b;
            std::complex<double> a0 = 0.0, a1 = 0.0;  // points whose digit is 0 (moves +step) or 1 (-step)
            for (uint32_t k = 0; k < size; ++k) {
              const uint32_t i = idx[k];
              (state.Bit(d, i, level) ? a1 : a0) += phase(f, i);
            }
            const double phi = 2.0 * kPi * hd * step;
            const std::complex<double> down(std::cos(phi), -std::sin(phi)), up(std::cos(phi), std::sin(phi));
            delta[f] = a0 * (down - 1.0) + a1 * (up - 1.0);
            change += weight[f] * (std::norm(s[f] + delta[f]) - std::norm(s[f]));
          }
          if (change < 0.0) {
            state.Toggle(d, level, prefix);
            for (size_t f = 0; f < kf; ++f) s[f] += delta[f];
            ++accepted;
          }
        }
      }
    }
    r.flips += accepted;
    r.sweeps = sweep + 1;
    if (accepted == 0) break;
  }
  r.objective = objective();
  r.points = state.Points();
  return r;
}

}  // namespace alignset

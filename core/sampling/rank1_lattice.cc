#include "core/sampling/rank1_lattice.h"

#include <cmath>
#include <numeric>
#include <tuple>
#include <utility>

#include "core/util/hash.h"
#include "core/sampling/sampler_util.h"

namespace alignset {
namespace {

int64_t Dot(int64_t ax, int64_t ay, int64_t bx, int64_t by) { return ax * bx + ay * by; }

// Squared length of the shortest nonzero vector of the lattice spanned by
// (ax, ay) and (bx, by) (Lagrange-Gauss reduction; coordinates stay below
// 2^21, so products fit in 64 bits).
int64_t ShortestSquared(int64_t ax, int64_t ay, int64_t bx, int64_t by) {
  if (Dot(ax, ay, ax, ay) > Dot(bx, by, bx, by)) {
    std::swap(ax, bx);
    std::swap(ay, by);
  }
  for (;;) {
    const int64_t aa = Dot(ax, ay, ax, ay);
    const int64_t ab = Dot(ax, ay, bx, by);
    // Nearest integer to ab / aa.
    const int64_t q = static_cast<int64_t>(std::llround(static_cast<double>(ab) / aa));
    bx -= q * ax;
    by -= q * ay;
    if (Dot(bx, by, bx, by) >= aa) return aa;
    std::swap(ax, bx);
    std::swap(ay, by);
  }
}

}  // namespace

bool IsFibonacci(uint32_t n, uint32_t* previous) {
  uint32_t a = 1, b = 2;  // F_2, F_3
  while (b < n) {
    const uint32_t c = a + b;
    a = b;
    b = c;
  }
  if (b == n && n >= 3) {
    if (previous) *previous = a;
    return true;
  }
  return false;
}

uint32_t Rank1InverseMod(uint32_t g, uint32_t n) {
  int64_t r0 = n, r1 = g % n, t0 = 0, t1 = 1;
  while (r1 != 0) {
    const int64_t q = r0 / r1;
    std::tie(r0, r1) = std::make_pair(r1, r0 - q * r1);
    std::tie(t0, t1) = std::make_pair(t1, t0 - q * t1);
  }
  return static_cast<uint32_t>(((t0 % n) + n) % n);
}

double Rank1MinDistanceTimesN(uint32_t n, uint32_t g) {
  return std::sqrt(static_cast<double>(ShortestSquared(1, g, 0, n)));
}

uint32_t Rank1Generator(uint32_t n) {
  if (n <= 2) return 1;
  uint32_t fib_previous = 0;
  if (IsFibonacci(n, &fib_previous)) return fib_previous;
  uint32_t best = 1;
  int64_t best_len = 0;
  for (uint32_t g = 1; g <= n / 2; ++g) {
    if (std::gcd(g, n) != 1) continue;
    const int64_t len = ShortestSquared(1, g, 0, n);
    if (len > best_len) {
      best_len = len;
      best = g;
    }
  }
  return best;
}

StatusOr<PointSet> Rank1Lattice(uint32_t n, uint64_t seed) {
  if (Status s = CheckSampleCount("rank1-lattice", n); !s.ok()) return s;
  const uint64_t g = Rank1Generator(n);
  Pcg32 rng(HashCombine(seed, 0x72616e6b31ULL));
  // The shift as whole columns (rows) plus one common offset inside them, so
  // that the shifted set keeps one point per column and row exactly.
  const uint64_t sx = rng.Uniform(n), sy = rng.Uniform(n);
  const double fx = rng.NextDouble(), fy = rng.NextDouble();
  PointSet points(n);
  for (uint64_t i = 0; i < n; ++i) {
    points[i] = {InStratum(static_cast<uint32_t>((i + sx) % n), fx, n),
                 InStratum(static_cast<uint32_t>((i * g + sy) % n), fy, n)};
  }
  return points;
}

}  // namespace alignset

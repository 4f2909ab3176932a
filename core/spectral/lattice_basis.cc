#include "core/spectral/lattice_basis.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <numeric>

#include "core/util/angles.h"

namespace alignset {
namespace {

int64_t Cross(const Frequency& o, const Frequency& a, const Frequency& b) {
  return (static_cast<int64_t>(a.a) - o.a) * (static_cast<int64_t>(b.b) - o.b) -
         (static_cast<int64_t>(a.b) - o.b) * (static_cast<int64_t>(b.a) - o.a);
}

// x, y with a x + b y = gcd(a, b) (>= 0).
int64_t ExtendedGcd(int64_t a, int64_t b, int64_t* x, int64_t* y) {
  if (b == 0) {
    *x = a >= 0 ? 1 : -1;
    *y = 0;
    return std::abs(a);
  }
  int64_t x1, y1;
  const int64_t g = ExtendedGcd(b, a % b, &x1, &y1);
  *x = y1;
  *y = x1 - (a / b) * y1;
  return g;
}

// Is angle (mod pi) inside [lo, hi] taken modulo pi (hi may exceed pi)?
bool InWindow(double angle, double lo, double hi) {
  if (hi - lo >= kPi) return true;
  double a = angle;
  while (a < lo) a += kPi;
  while (a - kPi >= lo) a -= kPi;
  return a <= hi;
}

double PolygonArea(const std::vector<Frequency>& poly) {
  double s = 0.0;
  for (size_t i = 0; i < poly.size(); ++i) {
    const Frequency& a = poly[i];
    const Frequency& b = poly[(i + 1) % poly.size()];
    s += static_cast<double>(a.a) * b.b - static_cast<double>(a.b) * b.a;
  }
  return 0.5 * std::abs(s);
}

// A candidate first basis vector p (primitive, p2 > 0 or p2 = 0 < p1), its
// angle and a q completing it (p1 q2 - p2 q1 = 1).
struct PrimitiveVector {
  int64_t p1, p2, q1, q2;
  double angle;
};

// Every candidate with max(|p1|, |p2|) <= max_component, p2 ascending, then
// p1 ascending: the order decides ties, so it is fixed.
std::vector<PrimitiveVector> PrimitiveVectors(int max_component) {
  std::vector<PrimitiveVector> out;
  for (int64_t p2 = 0; p2 <= max_component; ++p2) {
    for (int64_t p1 = -max_component; p1 <= max_component; ++p1) {
      if (!(p2 > 0 || p1 > 0)) continue;
      if (std::gcd(p1, p2) != 1) continue;
      int64_t x, y;
      ExtendedGcd(p1, p2, &x, &y);
      out.push_back({p1, p2, -y, x,
                     std::atan2(static_cast<double>(p2), static_cast<double>(p1))});
    }
  }
  return out;
}

// The frequency partition asks for the best basis hundreds of times per
// frequency set, once per key the server fills; the gcds and angles of the
// candidates are the same every time (and were most of that cost).
constexpr int kTabledComponent = 64;

const std::vector<PrimitiveVector>& TabledPrimitiveVectors() {
  static const std::vector<PrimitiveVector> table = PrimitiveVectors(kTabledComponent);
  return table;
}

}  // namespace

std::vector<Frequency> ConvexHull(std::vector<Frequency> pts) {
  std::sort(pts.begin(), pts.end(), [](const Frequency& u, const Frequency& v) {
    return u.a != v.a ? u.a < v.a : u.b < v.b;
  });
  pts.erase(std::unique(pts.begin(), pts.end()), pts.end());
  if (pts.size() < 3) return pts;
  std::vector<Frequency> hull(2 * pts.size());
  size_t k = 0;
  for (size_t i = 0; i < pts.size(); ++i) {
    while (k >= 2 && Cross(hull[k - 2], hull[k - 1], pts[i]) <= 0) --k;
    hull[k++] = pts[i];
  }
  for (size_t i = pts.size() - 1, lower = k + 1; i-- > 0;) {
    while (k >= lower && Cross(hull[k - 2], hull[k - 1], pts[i]) <= 0) --k;
    hull[k++] = pts[i];
  }
  hull.resize(k - 1);
  return hull;
}

BasisBox BoxInBasis(const std::vector<Frequency>& hull, const LatticeBasis& basis) {
  BasisBox box;
  box.basis = basis;
  for (const Frequency& v : hull) {
    box.m1 = std::max(box.m1, std::abs(basis.W1(v.a, v.b)));
    box.m2 = std::max(box.m2, std::abs(basis.W2(v.a, v.b)));
  }
  return box;
}

BasisBox BestBasis(const std::vector<Frequency>& hull, double angle_lo, double angle_hi,
                   double margin, int max_component,
                   const std::function<double(int64_t, int64_t)>& cost) {
  BasisBox best = BoxInBasis(hull, LatticeBasis{});
  double best_cost = cost(best.m1, best.m2);
  // A unimodular map keeps areas: the box [-m1, m1] x [-m2, m2] holds the
  // image of the hull, so 4 m1 m2 >= area, which prunes most candidates
  // before the search for the shear.
  const double area = PolygonArea(hull);
  std::vector<int64_t> w1(hull.size()), w2(hull.size());
  const std::vector<PrimitiveVector>& table = max_component <= kTabledComponent
                                                  ? TabledPrimitiveVectors()
                                                  : PrimitiveVectors(max_component);
  for (const PrimitiveVector& cand : table) {
    if (std::max(std::abs(cand.p1), cand.p2) > max_component) continue;
    if (!InWindow(cand.angle, angle_lo - margin, angle_hi + margin)) continue;
    const LatticeBasis b{cand.p1, cand.p2, cand.q1, cand.q2};
    int64_t m2 = 0, w1max = 0;
    for (size_t i = 0; i < hull.size(); ++i) {
      w1[i] = b.W1(hull[i].a, hull[i].b);
      w2[i] = b.W2(hull[i].a, hull[i].b);
      m2 = std::max(m2, std::abs(w2[i]));
      w1max = std::max(w1max, std::abs(w1[i]));
    }
    if (m2 > 0) {
      const auto m1_floor = static_cast<int64_t>(std::ceil(area / (4.0 * m2)));
      if (cost(m1_floor, m2) >= best_cost) continue;
    }
    // Shearing q -> q + k p maps w1 -> w1 - k w2; m1(k) is convex in k.
    auto m1_of = [&](int64_t k) {
      int64_t m = 0;
      for (size_t i = 0; i < hull.size(); ++i) m = std::max(m, std::abs(w1[i] - k * w2[i]));
      return m;
    };
    int64_t k_best = 0;
    if (m2 > 0) {
      int64_t lo = -w1max - 1, hi = w1max + 1;  // the minimum lies inside
      while (lo < hi) {
        const int64_t mid = lo + (hi - lo) / 2;
        if (m1_of(mid + 1) - m1_of(mid) >= 0) {
          hi = mid;
        } else {
          lo = mid + 1;
        }
      }
      k_best = lo;
    }
    const int64_t m1 = m1_of(k_best);
    const double c = cost(m1, m2);
    if (c < best_cost) {
      best_cost = c;
      best.basis = {cand.p1, cand.p2, b.q1 + k_best * cand.p1, b.q2 + k_best * cand.p2};
      best.m1 = m1;
      best.m2 = m2;
    }
  }
  return best;
}

}  // namespace alignset

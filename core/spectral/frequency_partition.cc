#include "core/spectral/frequency_partition.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numeric>
#include <tuple>
#include <unordered_set>

#include "core/util/angles.h"

namespace alignset {
namespace {

// Largest component of the first basis vector tried for an oblique group:
// the best p for a strip of length L and width W has |p| ~ sqrt(L / W) up to
// the quality of the rational approximation of its direction, a few tens for
// every N the project supports.
constexpr int kMaxBasisComponent = 40;
// Extra angle around a group's directions where p is searched.
constexpr double kAngleMargin = 3.0 * kPi / 180.0;
// More groups than this means K has no strip structure at this r0; the angle
// gap is widened until it fits.
constexpr size_t kMaxGroups = 32;

uint64_t Key(int64_t a, int64_t b) {
  if (b < 0 || (b == 0 && a < 0)) {
    a = -a;
    b = -b;
  }
  return (static_cast<uint64_t>(static_cast<uint32_t>(a)) << 32) |
         static_cast<uint64_t>(static_cast<uint32_t>(b));
}

double FoldedAngle(const Frequency& v) {
  double t = std::atan2(static_cast<double>(v.b), static_cast<double>(v.a));
  if (t < 0.0) t += kPi;
  if (t >= kPi) t -= kPi;
  return t;
}

double Norm2(const Frequency& v) {
  return static_cast<double>(v.a) * v.a + static_cast<double>(v.b) * v.b;
}

// A group of outer members, contiguous in angle: [lo, hi] with hi possibly
// beyond pi when the group wraps.
struct Group {
  std::vector<uint32_t> members;
  std::vector<Frequency> hull;  // of +-members
  double lo = 0.0, hi = 0.0;
  BasisBox box;
  double cost = 0.0;
};

// Hull of +-pts. Only the extreme points of each row can be hull vertices,
// so the rows are reduced to those first (linear time).
std::vector<Frequency> SymmetricHull(const std::vector<Frequency>& pts) {
  int32_t bmax = 0;
  for (const Frequency& v : pts) bmax = std::max(bmax, std::abs(v.b));
  const size_t rows = 2 * static_cast<size_t>(bmax) + 1;
  std::vector<int32_t> lo(rows, std::numeric_limits<int32_t>::max());
  std::vector<int32_t> hi(rows, std::numeric_limits<int32_t>::min());
  auto add = [&](int32_t a, int32_t b) {
    const size_t r = static_cast<size_t>(b + bmax);
    lo[r] = std::min(lo[r], a);
    hi[r] = std::max(hi[r], a);
  };
  for (const Frequency& v : pts) {
    add(v.a, v.b);
    add(-v.a, -v.b);
  }
  std::vector<Frequency> ext;
  for (size_t r = 0; r < rows; ++r) {
    if (lo[r] > hi[r]) continue;
    const int32_t b = static_cast<int32_t>(r) - bmax;
    ext.push_back({lo[r], b});
    if (hi[r] != lo[r]) ext.push_back({hi[r], b});
  }
  return ConvexHull(std::move(ext));
}

void Evaluate(Group* g, const PieceCost& cost) {
  g->box = BestBasis(g->hull, g->lo, g->hi, kAngleMargin, kMaxBasisComponent, cost);
  g->cost = cost(g->box.m1, g->box.m2);
}

Group Merge(const Group& a, const Group& b, double b_shift, const std::vector<Frequency>& k,
            const PieceCost& cost) {
  Group m;
  m.members = a.members;
  m.members.insert(m.members.end(), b.members.begin(), b.members.end());
  std::vector<Frequency> pts = a.hull;
  pts.insert(pts.end(), b.hull.begin(), b.hull.end());
  m.hull = ConvexHull(std::move(pts));
  m.lo = a.lo;
  m.hi = b.hi + b_shift;
  Evaluate(&m, cost);
  return m;
}

struct Candidate {
  std::vector<FrequencyPiece> pieces;
  double cost = std::numeric_limits<double>::infinity();
};

// K's entries by folded angle, with their squared norms.
struct AngleOrder {
  std::vector<std::pair<double, uint32_t>> by_angle;
  std::vector<double> norm2;
};

Candidate PartitionAt(const std::vector<Frequency>& k, const AngleOrder& order, double r0,
                      const PieceCost& cost) {
  Candidate out;
  const double r2 = r0 * r0 + 1e-9;
  std::vector<uint32_t> inner;
  std::vector<std::pair<double, uint32_t>> outer;
  for (uint32_t i = 0; i < k.size(); ++i) {
    if (order.norm2[i] <= r2) inner.push_back(i);
  }
  for (const auto& e : order.by_angle) {
    if (order.norm2[e.second] > r2) outer.push_back(e);
  }
  out.cost = 0.0;
  if (!inner.empty()) {
    // The centre is nearly round: its box in the identity basis is as good
    // as any.
    FrequencyPiece piece;
    for (uint32_t i : inner) {
      piece.box.m1 = std::max<int64_t>(piece.box.m1, std::abs(k[i].a));
      piece.box.m2 = std::max<int64_t>(piece.box.m2, std::abs(k[i].b));
    }
    piece.members = std::move(inner);
    out.cost += cost(piece.box.m1, piece.box.m2);
    out.pieces.push_back(std::move(piece));
  }
  if (outer.empty()) return out;

  // Split the circle of angles at gaps wider than `gap`; start right after
  // the widest gap so that no group straddles the start.
  const size_t m = outer.size();
  auto gap_after = [&](size_t i) {
    return i + 1 < m ? outer[i + 1].first - outer[i].first
                     : outer[0].first + kPi - outer[m - 1].first;
  };
  size_t widest = 0;
  for (size_t i = 1; i < m; ++i) {
    if (gap_after(i) > gap_after(widest)) widest = i;
  }
  double gap = 0.5 / r0;
  std::vector<Group> groups;
  for (;;) {
    groups.clear();
    const size_t start = (widest + 1) % m;
    double shift = 0.0;
    for (size_t s = 0; s < m; ++s) {
      const size_t i = (start + s) % m;
      if (s > 0 && i == 0) shift = kPi;  // wrapped past pi
      const double angle = outer[i].first + shift;
      if (groups.empty() || angle - groups.back().hi > gap) {
        groups.emplace_back();
        groups.back().lo = angle;
      }
      groups.back().hi = angle;
      groups.back().members.push_back(outer[i].second);
    }
    if (groups.size() <= kMaxGroups) break;
    gap *= 2.0;
  }
  for (Group& g : groups) {
    std::vector<Frequency> pts;
    for (uint32_t i : g.members) pts.push_back(k[i]);
    g.hull = SymmetricHull(pts);
    Evaluate(&g, cost);
  }

  // Greedy merging of neighbours (cyclically) while it pays. A merge only
  // changes the two pairs next to it, so every other pair's merged group is
  // kept from the rounds before (by the ids of its two groups), which makes
  // the merging linear in the groups instead of quadratic.
  std::vector<uint32_t> ids(groups.size());
  std::iota(ids.begin(), ids.end(), 0u);
  uint32_t next_id = static_cast<uint32_t>(groups.size());
  std::map<std::tuple<uint32_t, uint32_t, bool>, Group> merged_of;
  while (groups.size() >= 2) {
    double best_delta = 0.0;
    size_t best_i = 0;
    const Group* best_group = nullptr;
    const size_t pairs = groups.size() == 2 ? 1 : groups.size();
    for (size_t i = 0; i < pairs; ++i) {
      const size_t j = (i + 1) % groups.size();
      const bool wraps = j == 0;
      auto [it, fresh] = merged_of.try_emplace({ids[i], ids[j], wraps});
      if (fresh) it->second = Merge(groups[i], groups[j], wraps ? kPi : 0.0, k, cost);
      const double delta = it->second.cost - groups[i].cost - groups[j].cost;
      if (delta < best_delta) {
        best_delta = delta;
        best_i = i;
        best_group = &it->second;
      }
    }
    if (best_delta >= 0.0) break;
    const size_t j = (best_i + 1) % groups.size();
    groups[best_i] = *best_group;
    ids[best_i] = next_id++;
    groups.erase(groups.begin() + static_cast<std::ptrdiff_t>(j));
    ids.erase(ids.begin() + static_cast<std::ptrdiff_t>(j));
  }
  for (Group& g : groups) {
    FrequencyPiece piece;
    piece.box = g.box;
    piece.members = std::move(g.members);
    out.cost += g.cost;
    out.pieces.push_back(std::move(piece));
  }
  return out;
}

}  // namespace

int ContainedDiskRadius(const std::vector<Frequency>& k) {
  std::unordered_set<uint64_t> set;
  set.reserve(k.size() * 2);
  double max_norm2 = 0.0;
  for (const Frequency& v : k) {
    set.insert(Key(v.a, v.b));
    max_norm2 = std::max(max_norm2, Norm2(v));
  }
  const int limit = static_cast<int>(std::sqrt(max_norm2)) + 1;
  for (int r = 1; r <= limit; ++r) {
    const int64_t lo2 = static_cast<int64_t>(r - 1) * (r - 1), hi2 = static_cast<int64_t>(r) * r;
    for (int64_t b = 0; b <= r; ++b) {
      for (int64_t a = -r; a <= r; ++a) {
        const int64_t n2 = a * a + b * b;
        if (n2 <= lo2 || n2 > hi2 || (b == 0 && a <= 0)) continue;
        if (!set.count(Key(a, b))) return r - 1;
      }
    }
  }
  return limit;
}

std::vector<FrequencyPiece> PartitionFrequencies(const std::vector<Frequency>& k,
                                                 const PieceCost& cost) {
  if (k.empty()) return {};
  double max_norm = 0.0;
  for (const Frequency& v : k) max_norm = std::max(max_norm, std::sqrt(Norm2(v)));
  const double base = std::max(ContainedDiskRadius(k), 2);
  AngleOrder order;
  order.norm2.resize(k.size());
  order.by_angle.resize(k.size());
  for (uint32_t i = 0; i < k.size(); ++i) {
    order.norm2[i] = Norm2(k[i]);
    order.by_angle[i] = {FoldedAngle(k[i]), i};
  }
  std::sort(order.by_angle.begin(), order.by_angle.end());
  Candidate best;
  for (double f : {1.0, 1.5, 2.0, 3.0, 4.0, 6.0, 8.0, 12.0, 16.0}) {
    const double r0 = std::min(base * f, max_norm);
    Candidate c = PartitionAt(k, order, r0, cost);
    if (c.cost < best.cost) best = std::move(c);
    if (r0 >= max_norm) break;
  }
  return std::move(best.pieces);
}

}  // namespace alignset

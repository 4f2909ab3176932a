#include "core/align/canonical.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <utility>

#include "core/util/angles.h"

namespace alignset {
namespace {

// The four elements as they act on directions, in the order Canonicalize
// prefers them when several map the key onto the request.
constexpr std::array<AlignOps, 4> kDirectionElements = {{
    {false, false, false},  // identity
    {true, false, false},   // swap: t -> 90 - t
    {false, true, false},   // invert: t -> 180 - t
    {true, true, false},    // swap + invert: t -> t + 90
}};

int Mod180(int t) {
  const int r = t % 180;
  return r < 0 ? r + 180 : r;
}

// MapDirection on whole degrees, without floating point.
int MapWholeDegree(int t, AlignOps ops) {
  if (ops.swap) t = 90 - t;
  if (ops.invert) t = 180 - t;
  if (ops.invert_y) t = -t;
  return Mod180(t);
}

using Pair = std::pair<int, int>;

Pair Sorted(int a, int b) { return a <= b ? Pair{a, b} : Pair{b, a}; }

Pair MapPair(const Pair& p, AlignOps ops) {
  return Sorted(MapWholeDegree(p.first, ops), MapWholeDegree(p.second, ops));
}

// The lexicographically smallest sorted pair of the orbit of {a, b}.
Pair OrbitRepresentative(int a, int b) {
  Pair best = Sorted(a, b);
  for (const AlignOps& g : kDirectionElements) best = std::min(best, MapPair(Sorted(a, b), g));
  return best;
}

// All 4141 representatives in ascending (phi1, phi2) order: the enumeration
// walks pairs in that order and keeps those that are their own representative.
std::vector<CanonicalDirections> BuildPairKeys() {
  std::vector<CanonicalDirections> keys;
  for (int a = 0; a < 180; ++a) {
    for (int b = a; b < 180; ++b) {
      if (OrbitRepresentative(a, b) == Pair{a, b}) keys.push_back({2, a, b});
    }
  }
  return keys;
}

const std::vector<CanonicalDirections>& PairKeys() {
  static const std::vector<CanonicalDirections> keys = BuildPairKeys();
  return keys;
}

constexpr int kSingleKeys = 46;

// ServedDegree (the nearest whole degree, reduced to [0, 180)):
// core/util/directions.h.

// Nearest grid step (`steps` per degree) of a finite angle, reduced to
// [0, 180 steps).
int ServedSteps(double deg, int steps) {
  const int full = 180 * steps;
  const int r = static_cast<int>(std::round(ReduceDirection(deg) * steps));
  return ((r % full) + full) % full;
}

// Algorithm 1, in grid steps (`steps` per degree): t in [0, 180 steps).
AlignOps SingleDirectionOps(int t, int steps, int* phi) {
  if (t <= 45 * steps) {
    *phi = t;
    return {};
  }
  if (t <= 90 * steps) {
    *phi = 90 * steps - t;
    return {true, false, false};
  }
  if (t <= 135 * steps) {
    *phi = t - 90 * steps;
    return {true, true, false};
  }
  *phi = 180 * steps - t;
  return {false, true, false};
}

AlignOps SingleDirectionOps(int t, int* phi) { return SingleDirectionOps(t, 1, phi); }

// The one-direction key at `quarters` quarter degrees.
CanonicalDirections QuarterKey(int quarters) {
  return {1, quarters / 4, quarters / 4, quarters % 4};
}

constexpr uint64_t kGridBits = 53;
constexpr uint64_t kGridMask = (uint64_t{1} << kGridBits) - 1;

uint64_t ToFixed(double x) {
  if (!std::isfinite(x)) return 0;
  // Scaling by a power of two is exact; rint rounds half to even.
  const double scaled = Wrap01(x) * 0x1.0p53;
  return static_cast<uint64_t>(std::llrint(scaled)) & kGridMask;
}

double FromFixed(uint64_t q) { return static_cast<double>(q) * 0x1.0p-53; }

uint64_t Negate(uint64_t q) { return (~q + 1) & kGridMask; }

}  // namespace

double Phi1Degrees(const CanonicalDirections& key) { return key.phi1 + 0.25 * key.phi1_quarter; }
double Phi2Degrees(const CanonicalDirections& key) {
  return key.count == 1 ? Phi1Degrees(key) : static_cast<double>(key.phi2);
}

StatusOr<Canonicalization> Canonicalize(const std::vector<double>& directions_deg) {
  return Canonicalize(directions_deg, AngleGrid::kWholeDegree);
}

StatusOr<Canonicalization> Canonicalize(const std::vector<double>& directions_deg, AngleGrid grid) {
  if (directions_deg.size() != 1 && directions_deg.size() != 2) {
    return Status::InvalidArgument("expected one or two directions, got " +
                                   std::to_string(directions_deg.size()));
  }
  for (double d : directions_deg) {
    if (!std::isfinite(d)) {
      return Status::InvalidArgument("direction must be a finite angle in degrees, got " +
                                     std::to_string(d));
    }
  }
  Canonicalization out;
  out.requested_deg = directions_deg;
  if (directions_deg.size() == 1 && grid == AngleGrid::kQuarterDegree) {
    out.grid = grid;
    const int t = ServedSteps(directions_deg[0], 4);
    out.served_exact_deg = {0.25 * t};
    // The nearest whole degree for the integer field (ties away from zero,
    // 179.5 -> 0).
    out.served_deg = {ServedDegree(0.25 * t)};
    int phi = 0;
    out.ops = SingleDirectionOps(t, 4, &phi);
    out.key = QuarterKey(phi);
    return out;
  }
  for (double d : directions_deg) out.served_deg.push_back(ServedDegree(d));
  for (int d : out.served_deg) out.served_exact_deg.push_back(d);

  if (out.served_deg.size() == 1) {
    int phi = 0;
    out.ops = SingleDirectionOps(out.served_deg[0], &phi);
    out.key = {1, phi, phi};
    return out;
  }
  const Pair request = Sorted(out.served_deg[0], out.served_deg[1]);
  const Pair rep = OrbitRepresentative(request.first, request.second);
  out.key = {2, rep.first, rep.second};
  // Every element is its own inverse on directions, so the element that maps
  // the request onto the key also maps the key onto the request.
  for (const AlignOps& g : kDirectionElements) {
    if (MapPair(rep, g) == request) {
      out.ops = g;
      break;
    }
  }
  return out;
}

size_t CanonicalKeyCount(int count) {
  if (count == 1) return kSingleKeys;
  if (count == 2) return PairKeys().size();
  return 0;
}

size_t CanonicalKeyCount(int count, AngleGrid grid) {
  if (grid == AngleGrid::kWholeDegree) return CanonicalKeyCount(count);
  return count == 1 ? 4 * 45 + 1 : 0;
}

CanonicalDirections CanonicalKeyAt(int count, size_t index) {
  if (index >= CanonicalKeyCount(count)) return {};
  if (count == 1) {
    const int phi = static_cast<int>(index);
    return {1, phi, phi};
  }
  return PairKeys()[index];
}

CanonicalDirections CanonicalKeyAt(int count, size_t index, AngleGrid grid) {
  if (grid == AngleGrid::kWholeDegree) return CanonicalKeyAt(count, index);
  if (index >= CanonicalKeyCount(count, grid)) return {};
  return QuarterKey(static_cast<int>(index));
}

StatusOr<size_t> CanonicalKeyIndex(const CanonicalDirections& key, AngleGrid grid) {
  if (grid == AngleGrid::kWholeDegree) return CanonicalKeyIndex(key);
  if (key.count != 1) {
    return Status::InvalidArgument("the quarter-degree grid has one-direction keys only, not " +
                                   ToString(key));
  }
  if (key.phi1 < 0 || key.phi1 > 45 || key.phi2 != key.phi1 || key.phi1_quarter < 0 ||
      key.phi1_quarter > 3 || (key.phi1 == 45 && key.phi1_quarter != 0)) {
    return Status::InvalidArgument("not a canonical quarter-degree key: " + ToString(key));
  }
  return static_cast<size_t>(4 * key.phi1 + key.phi1_quarter);
}

StatusOr<size_t> CanonicalKeyIndex(const CanonicalDirections& key) {
  if (key.phi1_quarter != 0) {
    return Status::InvalidArgument("not a whole-degree key: " + ToString(key));
  }
  if (key.count == 1) {
    if (key.phi1 < 0 || key.phi1 >= kSingleKeys || key.phi2 != key.phi1) {
      return Status::InvalidArgument("not a canonical one-direction key: " + ToString(key));
    }
    return static_cast<size_t>(key.phi1);
  }
  if (key.count == 2) {
    const auto& keys = PairKeys();
    auto less = [](const CanonicalDirections& u, const CanonicalDirections& v) {
      return u.phi1 != v.phi1 ? u.phi1 < v.phi1 : u.phi2 < v.phi2;
    };
    auto it = std::lower_bound(keys.begin(), keys.end(), key, less);
    if (it == keys.end() || !(*it == key)) {
      return Status::InvalidArgument("not a canonical two-direction key: " + ToString(key));
    }
    return static_cast<size_t>(it - keys.begin());
  }
  return Status::InvalidArgument("a canonical key has 1 or 2 directions, not " +
                                 std::to_string(key.count));
}

Point2 AlignPoint(Point2 p, AlignOps ops) {
  uint64_t qx = ToFixed(p.x), qy = ToFixed(p.y);
  if (ops.swap) std::swap(qx, qy);
  if (ops.invert) qx = Negate(qx);
  if (ops.invert_y) qy = Negate(qy);
  return {FromFixed(qx), FromFixed(qy)};
}

PointSet Align(const PointSet& points, AlignOps ops) {
  PointSet out(points.size());
  for (size_t i = 0; i < points.size(); ++i) out[i] = AlignPoint(points[i], ops);
  return out;
}

AlignOps Inverse(AlignOps ops) {
  if (ops.swap) std::swap(ops.invert, ops.invert_y);
  return ops;
}

AlignOps Compose(AlignOps first, AlignOps second) {
  // Coordinate k of the result is coordinate pi_second(k) of `first`'s
  // result, so its sign picks up first's sign of that coordinate.
  AlignOps out;
  out.swap = first.swap != second.swap;
  const bool first_x = second.swap ? first.invert_y : first.invert;
  const bool first_y = second.swap ? first.invert : first.invert_y;
  out.invert = second.invert != first_x;
  out.invert_y = second.invert_y != first_y;
  return out;
}

double MapDirection(double deg, AlignOps ops) {
  double t = deg;
  if (ops.swap) t = 90.0 - t;
  if (ops.invert) t = 180.0 - t;
  if (ops.invert_y) t = -t;
  return ReduceDirection(t);
}

std::string FormatGridAngle(double deg) {
  char buf[48];
  std::snprintf(buf, sizeof buf, "%.6g", deg);
  return buf;
}

std::string ToString(const CanonicalDirections& key) {
  if (key.count == 1) return "phi=" + FormatGridAngle(Phi1Degrees(key));
  return "phi=" + std::to_string(key.phi1) + "," + std::to_string(key.phi2);
}

std::string ToString(AlignOps ops) {
  std::string s;
  auto add = [&s](const char* part) {
    if (!s.empty()) s += "+";
    s += part;
  };
  if (ops.swap) add("swap");
  if (ops.invert) add("invert_x");
  if (ops.invert_y) add("invert_y");
  return s.empty() ? "identity" : s;
}

}  // namespace alignset

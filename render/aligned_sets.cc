#include "render/aligned_sets.h"

#include <cmath>

#include "core/util/angles.h"

namespace alignset::render {

int ServedDegree(double theta_deg) {
  return static_cast<int>(std::lround(ReduceDirection(theta_deg))) % 180;
}

SetChoice ChooseSet(const PixelDirection& d, const AlignedPolicy& policy) {
  SetChoice c;
  auto is_axis = [](int deg) { return deg == 0 || deg == 90; };
  if (d.kind == PixelDirection::Kind::kNone) {
    if (policy.none == AlignedPolicy::None::kAxisSet) {
      c.kind = SetChoice::Kind::kOne;
      c.a = 0;
    }
    return c;
  }
  const int a = ServedDegree(d.theta1);
  c.kind = SetChoice::Kind::kOne;
  c.a = a;
  if (d.kind != PixelDirection::Kind::kTwo || !policy.two_directions) return c;
  const int b = ServedDegree(d.theta2);
  if (b == a || is_axis(b)) return c;
  if (is_axis(a)) {
    c.a = b;
    return c;
  }
  c.kind = SetChoice::Kind::kTwo;
  c.a = std::min(a, b);
  c.b = std::max(a, b);
  return c;
}

std::set<std::pair<int, int>> NeededPairs(const std::vector<PixelDirection>& directions,
                                          const AlignedPolicy& policy) {
  std::set<std::pair<int, int>> out;
  for (const PixelDirection& d : directions) {
    const SetChoice c = ChooseSet(d, policy);
    if (c.kind == SetChoice::Kind::kTwo) out.insert({c.a, c.b});
  }
  return out;
}

const PointSet* AlignedSetTable::One(int served_deg) const {
  if (served_deg < 0 || served_deg >= static_cast<int>(one.size())) return nullptr;
  return one[served_deg].empty() ? nullptr : &one[served_deg];
}

const PointSet* AlignedSetTable::Two(int a, int b) const {
  auto it = two.find({std::min(a, b), std::max(a, b)});
  return it == two.end() ? nullptr : &it->second;
}

}  // namespace alignset::render

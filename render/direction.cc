#include "render/direction.h"

#include <algorithm>
#include <cmath>

#include "render/parallel.h"
#include "core/util/angles.h"
#include "core/util/hash.h"

namespace alignset::render {

PixelDirection GeometryDirection(const PixelIntegrand& f) {
  struct Group {
    double anchor;
    double weight = 0.0;
    double offset_sum = 0.0;  // weighted signed axial offsets from the anchor
  };
  std::vector<EdgePiece> pieces = f.Discontinuities();
  std::sort(pieces.begin(), pieces.end(), [](const EdgePiece& a, const EdgePiece& b) {
    return a.length * a.jump > b.length * b.jump;
  });
  std::vector<Group> groups;
  double total = 0.0;
  for (const EdgePiece& p : pieces) {
    const double w = p.length * p.jump;
    total += w;
    Group* g = nullptr;
    for (Group& candidate : groups) {
      if (AxialDistanceDeg(candidate.anchor, p.normal_deg) <= kSameDirectionDeg) {
        g = &candidate;
        break;
      }
    }
    if (!g) {
      groups.push_back({p.normal_deg});
      g = &groups.back();
    }
    double off = p.normal_deg - g->anchor;
    if (off > 90.0) off -= 180.0;
    if (off < -90.0) off += 180.0;
    g->weight += w;
    g->offset_sum += w * off;
  }
  PixelDirection d;
  if (groups.empty() || total < kEdgeWeight) return d;
  std::sort(groups.begin(), groups.end(),
            [](const Group& a, const Group& b) { return a.weight > b.weight; });
  auto angle = [](const Group& g) { return ReduceDirection(g.anchor + g.offset_sum / g.weight); };
  d.kind = PixelDirection::Kind::kOne;
  d.theta1 = angle(groups[0]);
  d.confidence = groups[0].weight / total;
  for (size_t i = 1; i < groups.size(); ++i) {
    if (groups[i].weight < kSecondDirectionShare * groups[0].weight) break;
    if (AxialDistanceDeg(angle(groups[i]), d.theta1) < kSecondDirectionMinDeg) continue;
    d.kind = PixelDirection::Kind::kTwo;
    d.theta2 = angle(groups[i]);
    break;
  }
  return d;
}

std::vector<PixelDirection> GeometryDirections(const Scene& scene) {
  std::vector<PixelDirection> out(scene.size());
  ParallelFor(scene.size(), 2, [&](size_t i) { out[i] = GeometryDirection(scene.Pixel(i)); });
  return out;
}

std::vector<PixelDirection> DirectionEstimator::EstimateScene(const Scene& scene, uint64_t seed,
                                                              int threads) const {
  std::vector<PixelDirection> out(scene.size());
  ParallelFor(scene.size(), threads, [&](size_t i) {
    out[i] = Estimate(scene.Pixel(i), HashCombine(seed, i));
  });
  return out;
}

std::vector<PixelDirection> EstimateDirections(const Scene& scene, const DirectionEstimator& e,
                                               uint64_t seed, int threads) {
  return e.EstimateScene(scene, seed, threads);
}

}  // namespace alignset::render

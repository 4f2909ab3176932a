#include "bench/render/direction.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <numeric>

#include "bench/render/parallel.h"
#include "core/util/angles.h"
#include "core/util/hash.h"

namespace alignset::render {

double AxialDistanceDeg(double a, double b) {
  const double d = std::abs(ReduceDirection(a) - ReduceDirection(b));
  return std::min(d, 180.0 - d);
}

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

namespace {

class PlaceholderEstimator : public DirectionEstimator {
 public:
  explicit PlaceholderEstimator(int grid) : g_(grid) {}
  std::string name() const override { return "placeholder-grid" + std::to_string(g_); }
  int evaluations() const override { return g_ * g_; }
  PixelDirection Estimate(const PixelIntegrand& f, uint64_t) const override {
    std::vector<double> v(g_ * g_);
    for (int j = 0; j < g_; ++j) {
      for (int i = 0; i < g_; ++i) v[j * g_ + i] = f.Eval({(i + 0.5) / g_, (j + 0.5) / g_});
    }
    double sc = 0.0, ss = 0.0, total = 0.0;
    for (int b = -g_ / 2; b < (g_ + 1) / 2; ++b) {
      for (int a = 0; a < (g_ + 1) / 2; ++a) {
        if (a == 0 || b == 0) continue;  // the axes: the pixel's own boundary
        std::complex<double> sum = 0.0;
        for (int j = 0; j < g_; ++j) {
          for (int i = 0; i < g_; ++i) {
            sum += v[j * g_ + i] * std::polar(1.0, -2.0 * kPi * (a * i + b * j) / g_);
          }
        }
        const double p = std::norm(sum);
        const double phi = std::atan2(static_cast<double>(b), static_cast<double>(a));
        sc += p * std::cos(2 * phi);
        ss += p * std::sin(2 * phi);
        total += p;
      }
    }
    PixelDirection d;
    const double mean = std::abs(std::accumulate(v.begin(), v.end(), 0.0)) + 1e-12;
    if (total < 1e-6 * mean * mean) return d;
    const double coherence = std::hypot(sc, ss) / total;
    d.confidence = coherence;
    if (coherence < 0.3) return d;
    d.kind = PixelDirection::Kind::kOne;
    d.theta1 = ReduceDirection(0.5 * std::atan2(ss, sc) * 180.0 / kPi);
    return d;
  }

 private:
  int g_;
};

}  // namespace

std::unique_ptr<DirectionEstimator> MakePlaceholderEstimator(int grid) {
  return std::make_unique<PlaceholderEstimator>(grid);
}

std::vector<PixelDirection> GeometryDirections(const Scene& scene) {
  std::vector<PixelDirection> out(scene.size());
  ParallelFor(scene.size(), 2, [&](size_t i) { out[i] = GeometryDirection(scene.Pixel(i)); });
  return out;
}

std::vector<PixelDirection> EstimateDirections(const Scene& scene, const DirectionEstimator& e,
                                               uint64_t seed, int threads) {
  std::vector<PixelDirection> out(scene.size());
  ParallelFor(scene.size(), threads, [&](size_t i) {
    out[i] = e.Estimate(scene.Pixel(i), HashCombine(seed, i));
  });
  return out;
}

}  // namespace alignset::render

#include "core/analysis/folded_indicator_spectrum.h"

#include <algorithm>

namespace alignset {

std::vector<Polygon> TentFoldedImages(const Polygon& p) {
  std::vector<Polygon> out;
  for (int mx = 0; mx < 2; ++mx) {
    for (int my = 0; my < 2; ++my) {
      Polygon q;
      for (const Vec2& v : p) {
        q.push_back({mx ? 1.0 - 0.5 * v.x : 0.5 * v.x, my ? 1.0 - 0.5 * v.y : 0.5 * v.y});
      }
      // One mirror reverses the orientation.
      if (mx != my) std::reverse(q.begin(), q.end());
      out.push_back(std::move(q));
    }
  }
  return out;
}

std::vector<Polygon> TentFoldedHalf(const Polygon& p) {
  std::vector<Polygon> all = TentFoldedImages(p);
  return {std::move(all[0]), std::move(all[2])};
}

FoldedIndicatorSpectrum::FoldedIndicatorSpectrum(const Polygon& polygon, int radius, bool tabulate) {
  for (const Polygon& q : TentFoldedHalf(polygon)) parts_.emplace_back(q, radius, tabulate);
}

double FoldedIndicatorSpectrum::Energy(int hx, int hy) const {
  return SymmetricUnionEnergy(parts_.data(), parts_.size(), hx, hy);
}

}  // namespace alignset

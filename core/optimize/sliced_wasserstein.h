#pragma once

#include <cstdint>
#include <vector>

#include "core/util/point_set.h"

namespace alignset {

// Inverse CDF of the projection of the uniform unit square onto the unit
// direction at `deg`, centred at 0 (supplement Eq. 17). The projection's law
// is a symmetric trapezoid that depends only on {|cos|, |sin|}, so the angle is
// folded into [0°, 45°] first; Eq. 17 taken literally outside that range is
// wrong (at 120° by 0.7). u in [-1/2, 1/2].
double ProjectionInverseCdf(double u, double deg);

// Sorted target positions T_i of N projections onto `deg`: the inverse CDF at
// u_i = (i + 1/2)/N - 1/2, shifted back by (1/2, 1/2).d so they are positions of
// the square itself.
std::vector<double> WassersteinTargets(uint32_t n, double deg);

// L_SW = mean over directions d of (1/N) sum_i (sorted(S.d)_i - T_d,i)^2.
class SlicedWasserstein {
 public:
  SlicedWasserstein(uint32_t n, std::vector<double> directions_deg);

  // Returns the loss; if `gradient` is not null it is resized to N and set to
  // d L_SW / d s_j (sorting is piecewise constant, so this is exact almost
  // everywhere).
  //
  // The sort starts from the order of the previous call: an optimizer moves
  // points a little per step, so that order is nearly sorted and an insertion
  // sort finishes in about N steps (falling back to a full sort when it is
  // not). The result is the same either way: ties are broken by index. The
  // cached order makes concurrent calls on one object unsafe.
  double Evaluate(const PointSet& points, std::vector<Point2>* gradient) const;

  uint32_t n() const { return n_; }
  const std::vector<double>& directions() const { return directions_; }

 private:
  uint32_t n_;
  std::vector<double> directions_;
  std::vector<std::vector<double>> targets_;
  mutable std::vector<std::vector<uint32_t>> orders_;
};

}  // namespace alignset

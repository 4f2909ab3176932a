#pragma once

#include <vector>

#include "core/spectral/frequency_set.h"

namespace alignset {

// The energy of a power spectrum along each line through the origin: for a
// direction theta (radians, axial: theta and theta + pi are one line),
//   E(theta) = sum_v w_v exp(-d_v(theta)^2 / (2 sigma^2)),
//   d_v(theta) = |v| sin(angle(v) - theta),
// the weights w_v summed with a Gaussian in the distance d_v of frequency v
// from the line (in frequency units). Measured across the line rather than
// as an angle, one sigma covers the one or two lattice points that a line's
// energy falls on at every radius, and an aliased copy of the line (a
// parallel line a few units away) stays out.
class AngularEnergy {
 public:
  // weights[i] belongs to frequencies[i] (finite; the estimator's are >= 0,
  // its evidence weights may be negative); sigma > 0.
  AngularEnergy(const std::vector<Frequency>& frequencies, std::vector<double> weights,
                double sigma);

  // E(theta), summed over the frequencies within 6 sigma of the line.
  double At(double theta) const;

  // E at the centres theta_i = (i + 1/2) pi / bins of `bins` equal bins over
  // [0, pi), i.e. on doubled angles x = 2 theta at the bin centres
  // (i + 1/2) 2pi / bins (the axial data as a circular density).
  std::vector<double> Profile(int bins) const;

  // The weight of the frequencies whose angle lies within half_width of
  // theta (axially), and the total weight.
  double WeightNear(double theta, double half_width) const;
  // WeightNear at every bin centre theta_i = (i + 1/2) pi / bins.
  std::vector<double> WeightNearProfile(double half_width, int bins) const;
  double TotalWeight() const { return total_; }

  double sigma() const { return sigma_; }

 private:
  AngularEnergy() = default;
  std::vector<double> angle_;   // angle(v) in [0, pi)
  std::vector<double> radius_;  // |v|
  // v itself: d_v(theta) = b cos(theta) - a sin(theta), no trigonometry per
  // frequency.
  std::vector<double> a_, b_;
  std::vector<double> weight_;
  double sigma_ = 1.0;
  double total_ = 0.0;
};

// AxialDistance (radians): core/util/directions.h.

// Whether v lies within `band` frequency units of the line through the
// origin at theta: where a line's energy falls (its perpendicular spread is
// a few units whatever the radius, so this takes a narrow wedge at high
// radii and every angle of the lowest rings).
bool NearLine(const Frequency& v, double theta, double band);

}  // namespace alignset

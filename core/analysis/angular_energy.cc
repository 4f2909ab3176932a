#include "core/analysis/angular_energy.h"

#include <algorithm>
#include <cmath>

#include "core/util/angles.h"

namespace alignset {

AngularEnergy::AngularEnergy(const std::vector<Frequency>& frequencies,
                             std::vector<double> weights, double sigma)
    : weight_(std::move(weights)), sigma_(sigma) {
  angle_.resize(frequencies.size());
  radius_.resize(frequencies.size());
  a_.resize(frequencies.size());
  b_.resize(frequencies.size());
  for (size_t i = 0; i < frequencies.size(); ++i) {
    const double a = frequencies[i].a, b = frequencies[i].b;
    a_[i] = a;
    b_[i] = b;
    double t = std::atan2(b, a);
    if (t < 0.0) t += kPi;
    if (t >= kPi) t -= kPi;
    angle_[i] = t;
    radius_[i] = std::hypot(a, b);
    total_ += weight_[i];
  }
}

double AngularEnergy::At(double theta) const {
  const double reach = 6.0 * sigma_;
  const double inv = 1.0 / (2.0 * sigma_ * sigma_);
  const double c = std::cos(theta), s = std::sin(theta);
  double e = 0.0;
  for (size_t i = 0; i < angle_.size(); ++i) {
    if (weight_[i] == 0.0) continue;
    const double d = b_[i] * c - a_[i] * s;
    if (std::fabs(d) > reach) continue;
    e += weight_[i] * std::exp(-d * d * inv);
  }
  return e;
}

std::vector<double> AngularEnergy::Profile(int bins) const {
  std::vector<double> e(bins, 0.0);
  const double step = kPi / bins;
  const double reach = 6.0 * sigma_;
  const double inv = 1.0 / (2.0 * sigma_ * sigma_);
  std::vector<double> cos_t(bins), sin_t(bins);
  for (int k = 0; k < bins; ++k) {
    cos_t[k] = std::cos((k + 0.5) * step);
    sin_t[k] = std::sin((k + 0.5) * step);
  }
  for (size_t i = 0; i < angle_.size(); ++i) {
    if (weight_[i] == 0.0) continue;
    const double r = radius_[i];
    // Bins whose line passes within `reach` of v: |sin(angle - theta)| <=
    // reach / r; all of them when the radius is small.
    const double half = reach >= r ? kPi / 2.0 : std::asin(reach / r);
    const int first = static_cast<int>(std::floor((angle_[i] - half) / step - 0.5));
    const int last = static_cast<int>(std::ceil((angle_[i] + half) / step - 0.5));
    const int span = std::min(last - first, bins - 1);
    for (int k = first; k <= first + span; ++k) {
      const int bin = ((k % bins) + bins) % bins;
      const double d = b_[i] * cos_t[bin] - a_[i] * sin_t[bin];
      if (std::fabs(d) > reach) continue;  // the same cut as At
      e[bin] += weight_[i] * std::exp(-d * d * inv);
    }
  }
  return e;
}

double AngularEnergy::WeightNear(double theta, double half_width) const {
  double s = 0.0;
  for (size_t i = 0; i < angle_.size(); ++i) {
    if (AxialDistance(angle_[i], theta) <= half_width) s += weight_[i];
  }
  return s;
}

std::vector<double> AngularEnergy::WeightNearProfile(double half_width, int bins) const {
  // Prefix sums over the frequencies in angle order; a window is one or two
  // runs of that order (two when it wraps past 0 or pi).
  std::vector<size_t> order(angle_.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return angle_[a] < angle_[b]; });
  std::vector<double> sorted(order.size()), prefix(order.size() + 1, 0.0);
  for (size_t i = 0; i < order.size(); ++i) {
    sorted[i] = angle_[order[i]];
    prefix[i + 1] = prefix[i] + weight_[order[i]];
  }
  // Weight of the angles in [lo, hi] with 0 <= lo <= hi <= pi.
  auto range = [&](double lo, double hi) {
    const size_t a = std::lower_bound(sorted.begin(), sorted.end(), lo) - sorted.begin();
    const size_t b = std::upper_bound(sorted.begin(), sorted.end(), hi) - sorted.begin();
    return b > a ? prefix[b] - prefix[a] : 0.0;
  };
  std::vector<double> out(bins);
  if (half_width >= kPi / 2.0) {
    std::fill(out.begin(), out.end(), prefix.back());
    return out;
  }
  for (int i = 0; i < bins; ++i) {
    const double t = (i + 0.5) * kPi / bins;
    const double lo = t - half_width, hi = t + half_width;
    double sum = range(std::max(lo, 0.0), std::min(hi, kPi));
    if (lo < 0.0) sum += range(lo + kPi, kPi);
    if (hi > kPi) sum += range(0.0, hi - kPi);
    out[i] = sum;
  }
  return out;
}

bool NearLine(const Frequency& v, double theta, double band) {
  const double a = v.a, b = v.b;
  return std::hypot(a, b) * std::sin(AxialDistance(std::atan2(b, a), theta)) <= band;
}

}  // namespace alignset

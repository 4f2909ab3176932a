#include "core/analysis/expected_spectrum.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <string>

#include "core/spectral/frequency_set.h"
#include "core/util/angles.h"

namespace alignset {

StatusOr<ExpectedSpectrum> ComputeExpectedSpectrum(const std::vector<PointSet>& sets,
                                                   int max_frequency, SpectralEngine& engine) {
  if (sets.empty()) return Status::InvalidArgument("no point set to analyze");
  if (max_frequency < 1 || max_frequency > 1024) {
    return Status::InvalidArgument("maximum frequency " + std::to_string(max_frequency) +
                                   " out of range [1, 1024]");
  }
  const size_t n = sets[0].size();
  for (size_t i = 0; i < sets.size(); ++i) {
    if (sets[i].size() != n) {
      return Status::InvalidArgument("set " + std::to_string(i) + " has " +
                                     std::to_string(sets[i].size()) + " points, set 0 has " +
                                     std::to_string(n) + ": an expected spectrum needs one N");
    }
  }
  if (n == 0) return Status::InvalidArgument("empty point set");

  // One of each +-v pair (P is even), then mirrored into the box.
  const int m = max_frequency;
  std::vector<Frequency> half;
  for (int b = 0; b <= m; ++b) {
    for (int a = -m; a <= m; ++a) {
      if (b > 0 || a > 0) half.push_back({a, b});
    }
  }
  engine.SetFrequencies(half);
  std::vector<double> sum(half.size(), 0.0);
  const std::vector<double> ones(n, 1.0);
  std::vector<std::complex<double>> f;
  for (const PointSet& set : sets) {
    engine.EvaluateWeighted(set, ones, &f);
    for (size_t i = 0; i < half.size(); ++i) sum[i] += std::norm(f[i]);
  }

  ExpectedSpectrum out;
  out.max_frequency = m;
  out.point_count = n;
  out.set_count = static_cast<int>(sets.size());
  const int w = 2 * m + 1;
  out.power.assign(static_cast<size_t>(w) * w, 0.0);
  const double scale = 1.0 / (static_cast<double>(n) * static_cast<double>(sets.size()));
  for (size_t i = 0; i < half.size(); ++i) {
    const double p = sum[i] * scale;
    const Frequency& v = half[i];
    out.power[static_cast<size_t>(v.a + m) * w + (v.b + m)] = p;
    out.power[static_cast<size_t>(-v.a + m) * w + (-v.b + m)] = p;
  }
  return out;
}

std::vector<double> RadialProfile(const ExpectedSpectrum& s) {
  const int m = s.max_frequency;
  std::vector<double> sum(m + 1, 0.0), count(m + 1, 0.0);
  for (int a = -m; a <= m; ++a) {
    for (int b = -m; b <= m; ++b) {
      if (a == 0 && b == 0) continue;
      const long r = std::lround(std::hypot(a, b));
      if (r > m) continue;
      sum[r] += s.At(a, b);
      count[r] += 1.0;
    }
  }
  for (int r = 0; r <= m; ++r) sum[r] = count[r] > 0 ? sum[r] / count[r] : 0.0;
  return sum;
}

std::vector<double> DirectionalProfile(const ExpectedSpectrum& s, double deg) {
  const int m = s.max_frequency;
  const Vec2 d = UnitVector(deg);
  std::vector<double> sum(m + 1, 0.0), count(m + 1, 0.0);
  for (int a = -m; a <= m; ++a) {
    for (int b = -m; b <= m; ++b) {
      if (a == 0 && b == 0) continue;
      const double across = -a * d.y + b * d.x;
      if (std::abs(across) > 0.5 + 1e-9) continue;
      const long t = std::lround(std::abs(a * d.x + b * d.y));
      if (t < 1 || t > m) continue;
      sum[t] += s.At(a, b);
      count[t] += 1.0;
    }
  }
  for (int t = 1; t <= m; ++t) sum[t] = count[t] > 0 ? sum[t] / count[t] : NAN;
  return sum;
}

std::vector<double> AngularProfile(const ExpectedSpectrum& s, int bins, double r_min) {
  const int m = s.max_frequency;
  std::vector<double> sum(bins, 0.0), count(bins, 0.0);
  for (int a = -m; a <= m; ++a) {
    for (int b = 0; b <= m; ++b) {
      if (b == 0 && a <= 0) continue;  // one of each +-v pair
      const double r = std::hypot(a, b);
      if (r < r_min || r > m) continue;
      double angle = std::atan2(static_cast<double>(b), static_cast<double>(a)) * 180.0 / kPi;
      if (angle >= 180.0) angle -= 180.0;
      const int bin = std::min(bins - 1, static_cast<int>(angle / 180.0 * bins));
      sum[bin] += s.At(a, b);
      count[bin] += 1.0;
    }
  }
  for (int i = 0; i < bins; ++i) sum[i] = count[i] > 0 ? sum[i] / count[i] : 0.0;
  return sum;
}

}  // namespace alignset

#include "core/sampling/sampler_stratified.h"

#include <string>
#include <vector>

#include "core/util/hash.h"
#include "core/sampling/sampler_util.h"

namespace alignset {
namespace {

// Each sampler draws from its own stream, so that two samplers given one seed
// are not secretly correlated.
Pcg32 Rng(uint64_t seed, uint64_t sampler_tag) { return Pcg32(HashCombine(seed, sampler_tag)); }

StatusOr<uint32_t> SquareSide(const std::string& sampler, uint32_t n) {
  if (Status s = CheckSampleCount(sampler, n); !s.ok()) return s;
  const uint32_t m = ExactSquareRoot(n);
  if (m == 0) {
    uint32_t lo = static_cast<uint32_t>(std::sqrt(static_cast<double>(n)));
    while (static_cast<uint64_t>(lo) * lo > n) --lo;
    const uint64_t below = static_cast<uint64_t>(lo) * lo;
    const uint64_t above = static_cast<uint64_t>(lo + 1) * (lo + 1);
    return Status::InvalidArgument(sampler + " needs a square N (m x m strata); " +
                                   std::to_string(n) + " is not a square (nearest: " +
                                   std::to_string(below) + " or " + std::to_string(above) + ")");
  }
  return m;
}

enum class Shuffle { kIndependent, kCorrelated };

PointSet MultiJitter(uint32_t n, uint64_t seed, Shuffle shuffle, uint64_t tag) {
  uint32_t m = 0, k = 0;
  MultiJitterShape(n, &m, &k);
  Pcg32 rng = Rng(seed, tag);
  // Cell (i, j) (column i of m, row j of k) takes sub-column sigma_i(j) of
  // the k in its column and sub-row tau_j(i) of the m in its row: its x lies
  // in column i * k + sigma_i(j) of N, its y in row j * m + tau_j(i) of N.
  std::vector<std::vector<uint32_t>> sigma(m), tau(k);
  if (shuffle == Shuffle::kCorrelated) {
    const std::vector<uint32_t> s = RandomPermutation(k, rng), t = RandomPermutation(m, rng);
    for (auto& v : sigma) v = s;
    for (auto& v : tau) v = t;
  } else {
    for (auto& v : sigma) v = RandomPermutation(k, rng);
    for (auto& v : tau) v = RandomPermutation(m, rng);
  }
  PointSet points;
  points.reserve(n);
  for (uint32_t j = 0; j < k; ++j) {
    for (uint32_t i = 0; i < m; ++i) {
      const double u = rng.NextDouble(), v = rng.NextDouble();
      points.push_back({InStratum(i * k + sigma[i][j], u, n), InStratum(j * m + tau[j][i], v, n)});
    }
  }
  return points;
}

}  // namespace

StatusOr<PointSet> RandomPoints(uint32_t n, uint64_t seed) {
  if (Status s = CheckSampleCount("random", n); !s.ok()) return s;
  Pcg32 rng = Rng(seed, 1);
  PointSet points(n);
  for (Point2& p : points) {
    p.x = rng.NextDouble();
    p.y = rng.NextDouble();
  }
  return points;
}

StatusOr<PointSet> RegularGrid(uint32_t n) {
  auto m = SquareSide("grid", n);
  if (!m.ok()) return m.status();
  PointSet points;
  points.reserve(n);
  for (uint32_t j = 0; j < *m; ++j) {
    for (uint32_t i = 0; i < *m; ++i) points.push_back({InStratum(i, 0.5, *m), InStratum(j, 0.5, *m)});
  }
  return points;
}

StatusOr<PointSet> UniformJitter(uint32_t n, uint64_t seed) {
  auto m = SquareSide("uniform-jitter", n);
  if (!m.ok()) return m.status();
  Pcg32 rng = Rng(seed, 2);
  const double u = rng.NextDouble(), v = rng.NextDouble();
  PointSet points;
  points.reserve(n);
  for (uint32_t j = 0; j < *m; ++j) {
    for (uint32_t i = 0; i < *m; ++i) points.push_back({InStratum(i, u, *m), InStratum(j, v, *m)});
  }
  return points;
}

StatusOr<PointSet> Jittered(uint32_t n, uint64_t seed) {
  auto m = SquareSide("jittered", n);
  if (!m.ok()) return m.status();
  Pcg32 rng = Rng(seed, 3);
  PointSet points;
  points.reserve(n);
  for (uint32_t j = 0; j < *m; ++j) {
    for (uint32_t i = 0; i < *m; ++i) {
      const double u = rng.NextDouble(), v = rng.NextDouble();
      points.push_back({InStratum(i, u, *m), InStratum(j, v, *m)});
    }
  }
  return points;
}

StatusOr<PointSet> NRooks(uint32_t n, uint64_t seed) {
  if (Status s = CheckSampleCount("n-rooks", n); !s.ok()) return s;
  Pcg32 rng = Rng(seed, 4);
  const std::vector<uint32_t> rows = RandomPermutation(n, rng);
  PointSet points(n);
  for (uint32_t i = 0; i < n; ++i) {
    const double u = rng.NextDouble(), v = rng.NextDouble();
    points[i] = {InStratum(i, u, n), InStratum(rows[i], v, n)};
  }
  return points;
}

void MultiJitterShape(uint32_t n, uint32_t* columns, uint32_t* rows) {
  uint32_t m = static_cast<uint32_t>(std::sqrt(static_cast<double>(n)));
  while (m > 1 && (static_cast<uint64_t>(m) * m > n || n % m != 0)) --m;
  if (m == 0) m = 1;
  *columns = m;
  *rows = n / m;
}

StatusOr<PointSet> MultiJittered(uint32_t n, uint64_t seed) {
  if (Status s = CheckSampleCount("multi-jittered", n); !s.ok()) return s;
  return MultiJitter(n, seed, Shuffle::kIndependent, 5);
}

StatusOr<PointSet> CorrelatedMultiJittered(uint32_t n, uint64_t seed) {
  if (Status s = CheckSampleCount("cmj", n); !s.ok()) return s;
  return MultiJitter(n, seed, Shuffle::kCorrelated, 6);
}

}  // namespace alignset

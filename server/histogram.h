#pragma once

#include <cstdint>
#include <mutex>
#include <vector>

namespace alignset::server {

// A latency histogram in Prometheus' sense: counts of observations at or
// below each upper bound, their sum and their count. Observe takes one
// short lock (a call's end, an optimization's end), never on a per-point
// path.
class Histogram {
 public:
  // Upper bounds in seconds, ascending; +Inf is implied.
  explicit Histogram(std::vector<double> bounds);

  void Observe(double seconds);

  struct Snapshot {
    std::vector<double> bounds;
    std::vector<uint64_t> cumulative;  // one per bound, then +Inf (== count)
    double sum = 0.0;
    uint64_t count = 0;
  };
  Snapshot Take() const;

  // 1 ms ... 10 min: from a cache hit to a large optimization.
  static std::vector<double> LatencyBounds();

 private:
  const std::vector<double> bounds_;
  mutable std::mutex mu_;
  std::vector<uint64_t> counts_;  // per bucket (not cumulative), +Inf last
  double sum_ = 0.0;
  uint64_t count_ = 0;
};

}  // namespace alignset::server

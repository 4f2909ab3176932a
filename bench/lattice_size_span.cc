// What choosing a lattice's size could gain before any render: for step
// edges at angles every 1.7 degrees, the exact Cranley-Patterson variance
// (core/analysis/lattice_variance.h) of the aligned lattice of N points
// against the best of the lattices of N - span ... N points, each with the
// generator core/optimize/aligned_lattice.h chooses for the angle. The
// edges: theta - 0.5, theta, theta + 0.5 degrees through offsets -0.15, 0
// and 0.15 (a geometric mean). render/lattice_sets.h's size span makes the
// same choice by the search's own score instead.
//   alignset_lattice_size_span [N] [SPAN]     (default 256 16)
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "core/analysis/integrands.h"
#include "core/analysis/lattice_variance.h"
#include "core/optimize/aligned_lattice.h"

namespace {

double EdgeVariance(uint32_t n, uint32_t g, double theta) {
  double log_sum = 0.0;
  int count = 0;
  for (double dt : {-0.5, 0.0, 0.5}) {
    for (double offset : {-0.15, 0.0, 0.15}) {
      const auto edge = alignset::StepEdge(theta + dt, offset);
      log_sum += std::log(alignset::Rank1CpVariance(n, g, *edge, 2 * static_cast<int>(n)).head);
      ++count;
    }
  }
  return std::exp(log_sum / count);
}

}  // namespace

int main(int argc, char** argv) {
  const long n_arg = argc > 1 ? std::strtol(argv[1], nullptr, 10) : 256;
  const long span_arg = argc > 2 ? std::strtol(argv[2], nullptr, 10) : 16;
  if (n_arg < 32 || n_arg > 65536 || span_arg < 0 || span_arg > n_arg - 16) {
    std::fprintf(stderr, "usage: alignset_lattice_size_span [N in 32..65536] [SPAN in 0..N-16]\n");
    return 2;
  }
  const uint32_t n = static_cast<uint32_t>(n_arg), span = static_cast<uint32_t>(span_arg);
  std::vector<double> gains;
  std::printf("theta  variance(N=%u)  best size  its variance  gain\n", n);
  for (double theta = 0.25; theta < 45.0; theta += 1.7) {
    auto at_n = alignset::ChooseAlignedLatticeGenerator(n, {theta});
    if (!at_n.ok()) return 1;
    const double base = EdgeVariance(n, at_n->generator, theta);
    double best = base;
    uint32_t best_size = n;
    for (uint32_t size = n - span; size < n; ++size) {
      auto c = alignset::ChooseAlignedLatticeGenerator(size, {theta});
      if (!c.ok()) return 1;
      const double v = EdgeVariance(size, c->generator, theta);
      if (v < best) best = v, best_size = size;
    }
    gains.push_back(base / best);
    std::printf("%5.2f  %.3g  %u  %.3g  %.2f\n", theta, base, best_size, best, base / best);
  }
  double log_sum = 0.0;
  for (double g : gains) log_sum += std::log(g);
  std::sort(gains.begin(), gains.end());
  std::printf("gain: median %.2f, geometric mean %.2f\n", gains[gains.size() / 2],
              std::exp(log_sum / static_cast<double>(gains.size())));
  return 0;
}

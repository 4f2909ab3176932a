// End-to-end optimization time of alignset's profile (algorithm version 5)
// against the one before the low-frequency levers (version 2: the
// supplement's flat loss and K, at the engine's full accuracy), measured in
// the same run: for each N the two are run `--reps` times in alternating
// order (so drifting load hits both alike), and the medians and the median
// of the per-rep ratios are reported. --tolerance overrides the current
// profile's engine tolerance (1e-11 gives version 3's time).
//
//   alignset_profile_time [--n 4096,65536] [--reps 5] [--theta 30] [--threads 2]
//       [--tolerance T]
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

#include "core/optimize/optimizer.h"
#include "core/spectral/fast_engine.h"

namespace alignset {
namespace {

double Median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const size_t m = v.size() / 2;
  return v.size() % 2 ? v[m] : 0.5 * (v[m - 1] + v[m]);
}

double TimeOne(uint32_t n, double theta, int threads, bool current, double tolerance,
               uint64_t seed, int* iterations) {
  OptimizationProblem problem;
  problem.n = n;
  problem.directions = {theta};
  problem.seed = seed;
  problem.frequency_params = current ? DefaultFrequencyParams(n) : SupplementFrequencyParams(n);
  OptimizerOptions options = current ? OptimizerOptions{} : SupplementOptimizerOptions();
  if (current && tolerance > 0.0) options.engine_tolerance = tolerance;
  FastEngine engine(threads);
  const auto t0 = std::chrono::steady_clock::now();
  auto r = Optimize(problem, options, engine);
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (!r.ok()) {
    std::fprintf(stderr, "profile_time: %s\n", r.status().message().c_str());
    std::exit(1);
  }
  *iterations = r->iterations;
  return s;
}

int Main(int argc, char** argv) {
  std::vector<uint32_t> ns = {4096, 65536};
  int reps = 5, threads = 2;
  double theta = 30.0, tolerance = 0.0;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--help" || a == "-h") {
      std::printf("usage: alignset_profile_time [--n LIST] [--reps R] [--theta DEG] [--threads T] "
                  "[--tolerance T]\n");
      return 0;
    }
    if (i + 1 >= argc) {
      std::fprintf(stderr, "profile_time: %s needs a value\n", a.c_str());
      return 2;
    }
    const std::string v = argv[++i];
    if (a == "--n") {
      ns.clear();
      std::stringstream in(v);
      for (std::string item; std::getline(in, item, ',');) ns.push_back(std::stoul(item));
    } else if (a == "--reps") {
      reps = std::stoi(v);
    } else if (a == "--theta") {
      theta = std::stod(v);
    } else if (a == "--threads") {
      threads = std::stoi(v);
    } else if (a == "--tolerance") {
      tolerance = std::stod(v);
    } else {
      std::fprintf(stderr, "profile_time: unknown option %s\n", a.c_str());
      return 2;
    }
  }
  std::printf("n\tv2_median_s\tcurrent_median_s\tv2_iterations\tcurrent_iterations\t"
              "ratio_of_medians\t"
              "median_ratio\n");
  for (uint32_t n : ns) {
    std::vector<double> old_s, new_s, ratios;
    int old_it = 0, new_it = 0;
    for (int r = 0; r < reps; ++r) {
      const uint64_t seed = 1 + r;
      double o, c;
      if (r % 2 == 0) {
        o = TimeOne(n, theta, threads, false, 0.0, seed, &old_it);
        c = TimeOne(n, theta, threads, true, tolerance, seed, &new_it);
      } else {
        c = TimeOne(n, theta, threads, true, tolerance, seed, &new_it);
        o = TimeOne(n, theta, threads, false, 0.0, seed, &old_it);
      }
      std::fprintf(stderr, "# N=%u rep %d: v2 %.2f s, current %.2f s\n", n, r, o, c);
      old_s.push_back(o);
      new_s.push_back(c);
      ratios.push_back(c / o);
    }
    std::printf("%u\t%.3f\t%.3f\t%d\t%d\t%.3f\t%.3f\n", n, Median(old_s), Median(new_s), old_it,
                new_it, Median(new_s) / Median(old_s), Median(ratios));
    std::fflush(stdout);
  }
  return 0;
}

}  // namespace
}  // namespace alignset

int main(int argc, char** argv) { return alignset::Main(argc, argv); }

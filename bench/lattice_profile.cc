// The angular profile of a lattice: the exact Cranley-Patterson variance
// (a sum over the dual lattice, core/analysis/lattice_variance.h) of step
// edges at every direction, for the aligned lattice of (N, theta) and the
// unaligned best-Korobov lattice, beside Owen-Sobol's Monte Carlo figure at
// a few directions. It shows where a lattice pays for its aligned strip:
// narrow spikes at the directions of its shortest dual vectors.
//
//   alignset_lattice_profile --n 1024 --theta 30 [--step 0.5] [--window 1]
//   alignset_lattice_profile --n 1024 --theta 30 --check
//     the exact dual-lattice sums beside the CP Monte Carlo variance (40000
//     shifts, with its standard error) for the aligned edge and smooth members
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "core/analysis/integrands.h"
#include "core/analysis/lattice_variance.h"
#include "core/analysis/variance.h"
#include "core/optimize/aligned_lattice.h"
#include "core/sampling/owen_sobol.h"
#include "core/sampling/rank1_lattice.h"

namespace alignset {
namespace {

constexpr double kOffsets[] = {-0.2, -0.07, 0.07, 0.2};

double LatticeEdge(uint32_t n, uint32_t g, double deg) {
  double v = 0.0;
  for (double o : kOffsets) v += Rank1CpVariance(n, g, *StepEdge(deg, o), static_cast<int>(n)).extrapolated;
  return v / std::size(kOffsets);
}

double OwenSobolEdge(uint32_t n, double deg) {
  double v = 0.0;
  for (int s = 0; s < 16; ++s) {
    const PointSet p = OwenScrambledSobol(n, 1000 + s);
    for (double o : kOffsets) {
      auto f = StepEdge(deg, o);
      v += CranleyPattersonVariance(p, [&](const Point2& x) { return f->Value(x); }, f->Integral(),
                                    512, 12345).variance;
    }
  }
  return v / (16 * std::size(kOffsets));
}

}  // namespace
}  // namespace alignset

int main(int argc, char** argv) {
  using namespace alignset;
  uint32_t n = 1024;
  double theta = 30.0, step = 0.5;
  AlignedLatticeOptions options;
  options.threads = 0;
  bool check = false;
  for (int i = 1; i < argc; ++i) {
    if (std::string(argv[i]) == "--check") check = true;
  }
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string a = argv[i];
    if (a == "--check") {
      --i;
      continue;
    }
    if (a == "--n") n = static_cast<uint32_t>(std::atoi(argv[i + 1]));
    else if (a == "--theta") theta = std::atof(argv[i + 1]);
    else if (a == "--step") step = std::atof(argv[i + 1]);
    else if (a == "--window") options.window_deg = std::atof(argv[i + 1]);
    else {
      std::fprintf(stderr, "usage: alignset_lattice_profile --n N --theta DEG [--step S] [--window W]\n");
      return 2;
    }
  }
  auto choice = ChooseAlignedLatticeGenerator(n, {theta}, options);
  if (!choice.ok()) {
    std::fprintf(stderr, "alignset_lattice_profile: %s\n", choice.status().message().c_str());
    return 2;
  }
  const uint32_t korobov = Rank1Generator(n);
  if (check) {
    const PointSet points = Rank1LatticePoints(n, choice->generator, 1);
    std::printf("# N=%u theta=%g generator %u: exact (sum over the dual lattice, |h| <= 16 N, "
                "extrapolated) beside CP Monte Carlo (40000 shifts)\n",
                n, theta, choice->generator);
    std::printf("integrand\texact\tmonte_carlo\tstd_error\t(exact-mc)/se\n");
    const std::string t = std::to_string(theta);
    const std::vector<std::string> specs = {"step:" + t + ":0.07", "step:" + t + ":-0.2",
                                            "smoothstep:" + t, "disk", "boundary", "gaussian"};
    for (const std::string& spec : specs) {
      auto f = MakeIntegrand(spec);
      if (!f.ok()) return 2;
      const Integrand& g = **f;
      const double exact = Rank1CpVariance(n, choice->generator, g, static_cast<int>(16 * n)).extrapolated;
      const VarianceEstimate mc = CranleyPattersonVariance(
          points, [&](const Point2& x) { return g.Value(x); }, g.Integral(), 40000, 11);
      std::printf("%s\t%.4e\t%.4e\t%.1e\t%+.2f\n", spec.c_str(), exact, mc.variance, mc.std_error,
                  (exact - mc.variance) / mc.std_error);
    }
    return 0;
  }
  std::printf("# N=%u theta=%g: aligned generator %u (window +-%g deg), Korobov %u; exact dual-lattice "
              "CP variance of step edges (mean of offsets -0.2, -0.07, 0.07, 0.2); Owen-Sobol: "
              "16 scrambles x 512 shifts, every 15 degrees\n",
              n, theta, choice->generator, options.window_deg, korobov);
  std::printf("direction\taligned\tkorobov\towen_sobol\n");
  for (double d = 0.0; d < 180.0 - 1e-9; d += step) {
    const bool owen = std::fmod(d, 15.0) < 1e-9;
    std::printf("%g\t%.3e\t%.3e\t", d, LatticeEdge(n, choice->generator, d), LatticeEdge(n, korobov, d));
    if (owen) std::printf("%.3e\n", OwenSobolEdge(n, d)); else std::printf("-\n");
  }
  return 0;
}

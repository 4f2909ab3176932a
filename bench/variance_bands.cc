// Where an integrand's variance comes from: the exact CP-rotated variance
// (supplement Eq. 18) of sets read from files, against Owen-scrambled Sobol
// of the same N, split by frequency band |v| and by region: near the line
// through the origin along `--theta` (the edge normal, where a step's energy
// lies), near the axes (the square's own edges, where the periodized
// integrand jumps), and elsewhere. The rest beyond --radius is the Parseval
// tail, counted as white (P = 1) for both: that is exact for neither, so
// pick the radius to make it small against the bands that differ.
//
//   alignset_variance_bands --integrand SPEC --theta DEG [--radius 700]
//       [--near 8] [--scrambles 16] [--threads 2] SET_FILE...
//
// SET_FILE: any file `alignset optimize` writes (UTK text, .npy, .csv; a
// multi-set file counts every set). Each set is weighted equally; the sets
// must share N.
#include <array>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "client/point_file.h"
#include "core/analysis/exact_variance.h"
#include "core/analysis/integrands.h"
#include "core/sampling/owen_sobol.h"
#include "core/spectral/fast_engine.h"
#include "core/util/angles.h"

namespace alignset {
namespace {

constexpr double kBandEdges[] = {0, 2, 4, 8, 16, 32, 64, 128, 256, 512, 1024, 2048, 4096};
constexpr int kBands = sizeof(kBandEdges) / sizeof(kBandEdges[0]);

struct Breakdown {
  // [band][region]: 0 near the theta line, 1 near an axis, 2 elsewhere.
  std::vector<std::array<double, 3>> parts = std::vector<std::array<double, 3>>(kBands);
  double tail = 0.0;
  double total = 0.0;
};

int BandOf(double r) {
  int b = 0;
  while (b + 1 < kBands && r >= kBandEdges[b + 1]) ++b;
  return b;
}

Breakdown Decompose(const std::vector<PointSet>& sets, const IntegrandEnergy& f, double theta,
                    double near, SpectralEngine& engine) {
  Breakdown out;
  const double t = DegToRad(theta);
  const double nx = std::cos(t), ny = std::sin(t);
  const double share = 1.0 / static_cast<double>(sets.size());
  for (const PointSet& points : sets) {
    const DiskSpectrum spectrum = ComputeDiskSpectrum(points, f.radius, engine);
    const double n = static_cast<double>(points.size());
    for (size_t i = 0; i < spectrum.frequencies.size(); ++i) {
      const Frequency& v = spectrum.frequencies[i];
      // Both halves of +-v: the half disk holds one of each pair.
      const double c = 2.0 * std::norm(spectrum.f[i]) * f.energy[i] / (n * n) * share;
      const double off_line = std::abs(-ny * v.a + nx * v.b);
      const int region = off_line <= near ? 0 : (std::abs(v.a) <= near || std::abs(v.b) <= near) ? 1 : 2;
      out.parts[BandOf(std::hypot(v.a, v.b))][region] += c;
    }
    const ExactVariance ev = ExactCpVariance(spectrum, f);  // the tail and the total
    out.tail += ev.tail_estimate * share;
    out.total += ev.variance * share;
  }
  return out;
}

int Main(int argc, char** argv) {
  std::string spec;
  double theta = NAN, near = 8.0;
  int radius = 700, scrambles = 16, threads = 2;
  std::vector<std::string> files;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto next = [&]() -> std::string {
      if (i + 1 >= argc) {
        std::fprintf(stderr, "variance_bands: %s needs a value\n", a.c_str());
        std::exit(2);
      }
      return argv[++i];
    };
    if (a == "--help" || a == "-h") {
      std::printf("usage: alignset_variance_bands --integrand SPEC --theta DEG [--radius R] "
                  "[--near D] [--scrambles K] [--threads T] SET_FILE...\n");
      return 0;
    } else if (a == "--integrand") {
      spec = next();
    } else if (a == "--theta") {
      theta = std::stod(next());
    } else if (a == "--radius") {
      radius = std::stoi(next());
    } else if (a == "--near") {
      near = std::stod(next());
    } else if (a == "--scrambles") {
      scrambles = std::stoi(next());
    } else if (a == "--threads") {
      threads = std::stoi(next());
    } else if (!a.empty() && a[0] == '-') {
      std::fprintf(stderr, "variance_bands: unknown option %s\n", a.c_str());
      return 2;
    } else {
      files.push_back(a);
    }
  }
  if (spec.empty() || std::isnan(theta) || files.empty() || radius < 1 || scrambles < 1) {
    std::fprintf(stderr, "variance_bands: needs --integrand, --theta and at least one set file "
                         "(radius and scrambles >= 1)\n");
    return 2;
  }
  auto f = MakeIntegrand(spec);
  if (!f.ok()) {
    std::fprintf(stderr, "variance_bands: %s\n", f.status().message().c_str());
    return 2;
  }
  std::vector<PointSet> sets;
  for (const std::string& path : files) {
    auto read = cli::ReadPointSets(path);
    if (!read.ok()) {
      std::fprintf(stderr, "variance_bands: %s: %s\n", path.c_str(), read.status().message().c_str());
      return 2;
    }
    for (PointSet& s : *read) sets.push_back(std::move(s));
  }
  const uint32_t n = static_cast<uint32_t>(sets.front().size());
  for (const PointSet& s : sets) {
    if (s.size() != n) {
      std::fprintf(stderr, "variance_bands: the sets must share N (%u and %zu)\n", n, s.size());
      return 2;
    }
  }
  std::vector<PointSet> owen;
  for (int s = 0; s < scrambles; ++s) owen.push_back(OwenScrambledSobol(n, 1000 + s));
  FastEngine engine(threads);
  // f^ once for both sides and every set: it costs more than a set's spectrum.
  const IntegrandEnergy energy = ComputeIntegrandEnergy(radius, **f);
  const Breakdown mine = Decompose(sets, energy, theta, near, engine);
  const Breakdown base = Decompose(owen, energy, theta, near, engine);

  std::printf("# %s, N = %u, %zu set(s) against Owen-Sobol (%d scrambles); exact Eq. 18 over "
              "|v| <= %d, regions: within %g of the %g-degree line, within %g of an axis, rest\n",
              spec.c_str(), n, sets.size(), scrambles, radius, near, theta, near);
  std::printf("band\tline_set\tline_owen\taxes_set\taxes_owen\trest_set\trest_owen\n");
  for (int b = 0; b < kBands; ++b) {
    if (kBandEdges[b] >= radius) break;
    const double hi = b + 1 < kBands ? std::min<double>(kBandEdges[b + 1], radius) : radius;
    std::printf("[%g,%g)", kBandEdges[b], hi);
    for (int r = 0; r < 3; ++r) {
      std::printf("\t%.3e\t%.3e", mine.parts[b][r], base.parts[b][r]);
    }
    std::printf("\n");
  }
  std::printf("tail beyond %d (white)\t%.3e\t%.3e\n", radius, mine.tail, base.tail);
  std::printf("total\t%.3e\t%.3e\tratio %.3f\n", mine.total, base.total, mine.total / base.total);
  return 0;
}

}  // namespace
}  // namespace alignset

int main(int argc, char** argv) { return alignset::Main(argc, argv); }

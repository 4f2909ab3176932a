// What any lattice could give, not what a search chose: for every rank-1
// lattice of N points with a generator coprime to N, or every integer lattice
// of N points, plain or tent-folded after its shift, the exact
// Cranley-Patterson variance of the step edges bench/construction_eval.py
// measures: normals theta + D and theta - D (D = 0, 0.5, 1, 2 degrees), each
// through K parallel edges at offsets in [-1/4, 1/4], the mean over both
// signs and the offsets. Issue 25 asks one construction to be 8x (N = 1024) or
// 20x (4096) below Owen-Sobol at D = 0, 3x at D = 1 and 1x at D = 2 together;
// bench/lattice_frontier.py reads these figures beside Owen-Sobol's from the
// independent evaluator and says whether any lattice reaches them.
//
// The sum runs over the dual points within F N (F = 2 by default) and is
// extrapolated as Rank1CpVariance does (2 S(R) - S(R/2): an edge's energy
// along its line falls like 1/|h|^2).
//
//   alignset_lattice_frontier N plain|tent THETA[,THETA...] [--radius F]
//       [--offsets K] [--g G,...] [--deltas D,...] [--integer-lattices]
//
// --offsets: K = 8 by default, the evaluator's. A lattice's variance swings
// with the offset (a folded one's by 2-10x within a few hundredths), and 8
// offsets 1/14 apart can fall on its troughs or its crests, so the best of
// many lattices at 8 is partly luck; 101 give the mean over a continuum of
// edges. --g: only these lattices (generators, or a/b/d with
// --integer-lattices). --deltas: only these D (the others print nan).
// --integer-lattices: every integer lattice of N points (DualBasis).
//
// Output (TSV on stdout): mode N theta g edge0 edge0.5 edge1 edge2, g the
// generator, or a/b/d for a lattice without a generator coprime to N.
// Progress on stderr, one line per theta.
#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <numeric>
#include <optional>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <CLI/CLI.hpp>

#include "core/analysis/convex_polygon.h"
#include "core/analysis/folded_indicator_spectrum.h"
#include "core/analysis/integer_indicator_spectrum.h"
#include "core/analysis/integrands.h"
#include "core/spectral/frequency_set.h"

namespace {

constexpr double kDeltas[] = {0.0, 0.5, 1.0, 2.0};

// The edge {p : (p - c) . n >= 0}, c = (1/2, 1/2) + offset n: core's step
// edge, whose centre and offset are construction_eval.py's. Offsets within
// [-1/4, 1/4] never clip it away.
alignset::Polygon EdgePolygon(double normal_deg, double offset) {
  return alignset::StepEdge(normal_deg, offset)->pieces().front().polygon;
}

// A lattice of N points by its dual, a sublattice of Z^2 of index N in
// Hermite normal form with basis (a, 0), (b, d), a d = N, 0 <= b < a. The
// rank-1 lattice of generator g is a = N, b = N - g, d = 1 (its dual
// h_x + g h_y = 0 mod N); --integer-lattices scores every (a, b, d), the
// other integer lattices of N points among them.
struct DualBasis {
  int64_t a = 0, b = 0, d = 0;
  uint32_t generator = 0;  // 0 unless rank-1 with a generator coprime to N
};

// The nonzero dual points within `radius`, one of each +-h pair.
std::vector<alignset::Frequency> DualHalfDisk(const DualBasis& basis, int radius) {
  std::vector<alignset::Frequency> out;
  const int64_t r = radius, r2 = r * r;
  for (int64_t j = 0; basis.d * j <= r; ++j) {
    const int64_t hy = basis.d * j;
    const int64_t base = (basis.b * j) % basis.a;
    for (int64_t hx = base - ((base + r) / basis.a) * basis.a; hx <= r; hx += basis.a) {
      if (hy == 0 && hx <= 0) continue;
      if (hx * hx + hy * hy > r2) continue;
      out.push_back({static_cast<int32_t>(hx), static_cast<int32_t>(hy)});
    }
  }
  return out;
}

// One scored edge's spectrum, plain or folded.
struct EdgeSpectrum {
  std::optional<alignset::IntegerIndicatorSpectrum> plain;
  std::optional<alignset::FoldedIndicatorSpectrum> folded;
  int delta_index = 0;
  double Energy(int hx, int hy) const { return plain ? plain->Energy(hx, hy) : folded->Energy(hx, hy); }
};

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Every lattice's exact variance on the evaluator's edges (bench/lattice_frontier.py reads it)."};
  uint32_t n = 0;
  std::string mode;
  std::vector<double> thetas;
  double radius_factor = 2.0;
  long offsets = 8;
  std::vector<std::string> only;  // generators, or a/b/d with --integer-lattices
  bool integer_lattices = false;
  std::vector<double> deltas(std::begin(kDeltas), std::end(kDeltas));
  app.add_option("N", n, "points")->required()->check(CLI::Range(16u, 65536u));
  app.add_option("mode", mode, "plain or tent (folded after the shift)")
      ->required()
      ->check(CLI::IsMember({"plain", "tent"}));
  app.add_option("thetas", thetas, "edge normals in degrees, comma-separated")->required()->delimiter(',');
  app.add_option("--radius", radius_factor, "dual points within F N")->check(CLI::Range(0.25, 8.0));
  app.add_option("--offsets", offsets, "edges per normal, evenly in [-1/4, 1/4]")->check(CLI::Range(2L, 1001L));
  app.add_option("--g", only, "only these generators (a/b/d with --integer-lattices)")->delimiter(',');
  app.add_option("--deltas", deltas, "only these of 0, 0.5, 1, 2 degrees off")
      ->delimiter(',')
      ->check(CLI::IsMember({0.0, 0.5, 1.0, 2.0}));
  app.add_flag("--integer-lattices", integer_lattices, "every integer lattice of N points");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : 2;  // help is 0, a usage error 2, as the alignset CLI's
  }
  const bool folded = mode == "tent";
  const int radius = static_cast<int>(std::lround(radius_factor * n));
  const double half = 0.5 * radius;

  // Folding mirrors the lattice's y as well as the edge's, so g and N - g
  // give the same folded variance: half the generators suffice there.
  std::vector<DualBasis> lattices;
  auto name_of = [](const DualBasis& l) {
    return l.generator != 0 ? std::to_string(l.generator)
                            : std::to_string(l.a) + "/" + std::to_string(l.b) + "/" + std::to_string(l.d);
  };
  auto wanted = [&](const DualBasis& l) {
    return only.empty() || std::find(only.begin(), only.end(), name_of(l)) != only.end();
  };
  if (integer_lattices) {
    for (int64_t a = 1; a <= n; ++a) {
      if (n % a != 0) continue;
      for (int64_t b = 0; b < a; ++b) {
        const int64_t d = n / a;
        const uint32_t g = d == 1 && std::gcd<int64_t>(b, n) == 1 ? static_cast<uint32_t>((n - b) % n) : 0;
        if (wanted({a, b, d, g})) lattices.push_back({a, b, d, g});
      }
    }
  } else {
    for (uint32_t g = 1; g < n; ++g) {
      if (std::gcd(g, n) != 1) continue;
      const DualBasis l{n, (n - g) % n, 1, g};
      if (only.empty() ? (!folded || g <= n / 2) : wanted(l)) lattices.push_back(l);
    }
  }
  const unsigned threads = std::max(1u, std::min(2u, std::thread::hardware_concurrency()));

  std::printf("mode\tN\ttheta\tg\tedge0\tedge0.5\tedge1\tedge2\n");
  for (double theta : thetas) {
    std::vector<EdgeSpectrum> edges;
    for (int di = 0; di < 4; ++di) {
      const double d = kDeltas[di];
      if (std::find(deltas.begin(), deltas.end(), d) == deltas.end()) continue;
      for (double sign : d == 0.0 ? std::vector<double>{1.0} : std::vector<double>{1.0, -1.0}) {
        for (long o = 0; o < offsets; ++o) {
          const double offset = -0.25 + 0.5 * static_cast<double>(o) / static_cast<double>(offsets - 1);
          const alignset::Polygon p = EdgePolygon(theta + sign * d, offset);
          EdgeSpectrum e;
          e.delta_index = di;
          if (folded) {
            e.folded.emplace(p, radius);
          } else {
            e.plain.emplace(p, radius);
          }
          edges.push_back(std::move(e));
        }
      }
    }
    std::vector<std::array<double, 4>> result(lattices.size());
    std::atomic<size_t> next{0};
    auto work = [&] {
      for (size_t i; (i = next.fetch_add(1)) < lattices.size();) {
        const auto dual = DualHalfDisk(lattices[i], radius);
        // Which dual points lie within R / 2, once for all the edges.
        std::vector<char> inside(dual.size());
        for (size_t k = 0; k < dual.size(); ++k) {
          inside[k] = std::hypot(static_cast<double>(dual[k].a), static_cast<double>(dual[k].b)) <= half;
        }
        std::array<double, 4> sum{}, count{};
        for (const EdgeSpectrum& e : edges) {
          double head = 0.0, inner = 0.0;
          for (size_t k = 0; k < dual.size(); ++k) {
            const double v = 2.0 * e.Energy(dual[k].a, dual[k].b);
            head += v;
            if (inside[k]) inner += v;
          }
          sum[e.delta_index] += std::max(head, 2.0 * head - inner);
          count[e.delta_index] += 1.0;
        }
        // A delta not asked for is printed as nan.
        for (int d = 0; d < 4; ++d) result[i][d] = count[d] > 0 ? sum[d] / count[d] : std::nan("");
      }
    };
    std::vector<std::thread> pool;
    for (unsigned t = 0; t < threads; ++t) pool.emplace_back(work);
    for (auto& t : pool) t.join();
    for (size_t i = 0; i < lattices.size(); ++i) {
      const std::string name = name_of(lattices[i]);
      std::printf("%s\t%u\t%g\t%s\t%.4e\t%.4e\t%.4e\t%.4e\n", mode.c_str(), n, theta, name.c_str(), result[i][0],
                  result[i][1], result[i][2], result[i][3]);
    }
    std::fflush(stdout);
    std::fprintf(stderr, "%s N=%u theta=%g: %zu lattices\n", mode.c_str(), n, theta, lattices.size());
  }
  return 0;
}

// The integrand family benchmark: the CP variance (or, for the "noshift"
// members, the squared error of the set as it is) of aligned sets against
// Owen-scrambled Sobol (the mean of
// `--scrambles` scrambles, same shifts) on every integrand of the family, at
// several N and angles, with ratios and fitted slopes; optionally the exact
// Eq. 18 variance beside the Monte Carlo figure.
//
//   alignset_integrand_family --n 256,1024,4096 --theta 10,30,45 [--theta2 100]
//       [--seeds 1] [--scrambles 16] [--shifts 2048] [--offsets 8] [--shift-seed S] [--exact]
//       [--construction optimized|lattice|lattice-start|net|warm --warm-root DEG
//        [--warm-iterations I --warm-step DEG --warm-lr-scale X --warm-warmup F
//         --warm-warmup-max N --warm-anneal R --warm-zero R]]
//       [--first-seed S]
//       [--profile current|supplement] [--p P --wp P --warmup F --stratify 0|1
//        --zero R --margin M --kl X --kw X --kr X --sw-weight C --iterations I --lr LR
//        --tolerance T]
//       [--cache DIR] [--out results.tsv] [--members NAME,NAME,...]
//
// --members evaluates only the named members (a screen of one lever on the
// members it is meant to move costs seconds at N = 65536, where the whole
// family, its 1024 Gaussians under 64 shifts, takes minutes a set).
//
// --profile supplement is algorithm version 2 (the flat loss on the
// supplement's K, SupplementOptimizerOptions); the knobs after it override
// single options of the chosen profile (--kl/--kw/--kr multiply the
// profile's strip length, strip width and disk radius).
//
// Step-type integrands (steps and the smoothed step) are averaged over
// `--offsets` parallel edges at offsets spread over [-1/4, 1/4] along the
// normal, as bench/quality.py does, so a figure is a property of the set and
// not of one lucky edge position. Optimized sets and baseline figures are
// cached in --cache (keyed by every option), so sweeps re-use them.
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <functional>
#include <fstream>
#include <map>
#include <memory>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "core/analysis/exact_variance.h"
#include "core/analysis/integrands.h"
#include "core/analysis/variance.h"
#include "core/optimize/aligned_lattice.h"
#include "core/optimize/aligned_net.h"
#include "core/optimize/optimizer.h"
#include "core/sampling/owen_sobol.h"
#include "core/spectral/fast_engine.h"
#include "core/util/hash.h"

namespace alignset {
namespace {

// The CP shifts' seed every table before --shift-seed used; the baseline cache
// keys of runs with it carry no seed, so they stay valid.
constexpr uint64_t kDefaultShiftSeed = 12345;

struct Options {
  std::vector<uint32_t> n = {256, 1024, 4096};
  std::vector<double> theta = {10, 30, 45};
  double theta2 = NAN;
  int seeds = 1;
  int first_seed = 1;
  int scrambles = 16;
  int shifts = 2048;
  int offsets = 8;
  // CP shifts per Gaussian of the 1024 in `gaussians cp`.
  int gaussian_shifts = 8;
  // The seed of the CP shifts, the same for every set and the baselines
  // (common random numbers); another seed measures the evaluator's own noise.
  uint64_t shift_seed = kDefaultShiftSeed;
  bool exact = false;
  // Multipliers of the profile's strip length, width and disk radius.
  double kl = 1.0, kw = 1.0, kr = 1.0;
  bool supplement = false;
  // "optimized" (the descent, the default), "lattice" (the aligned rank-1
  // lattice; realizations by seed, nothing cached) or "lattice-start" (the
  // descent from the aligned lattice instead of Owen-Sobol).
  std::string construction = "optimized";
  // "warm": the set for theta is reached from a cold set at `warm_root`
  // (same theta2) by a chain of steps (1 degree unless warm_step), each a
  // descent with WarmStartOptions (the service's key lineage,
  // core/align/key_lineage.h) from the previous step's set; the knobs below override single options
  // of it (warm_iterations 0: the profile's warm budget).
  double warm_root = NAN;
  int warm_iterations = 0;
  // Degrees per warm step (0: one step from the root straight to theta).
  double warm_step = 1.0;
  // The warm first step over the default (0: the profile's, WarmStartOptions).
  double warm_lr_scale = 0.0;
  double warm_warmup = -1.0;  // < 0: the profile's warm_warmup_fraction
  double warm_anneal = 1.0;
  // --construction net: the aligned net's options (core/optimize/aligned_net.h).
  AlignedNetOptions net;
  double warm_zero = -1.0;  // < 0: the profile's zero radius
  int threads = 2;
  OptimizerOptions opt;
  std::string cache = "build/bench-cache";
  std::string out;
  std::vector<std::string> members;  // empty: all
};

std::vector<double> ParseList(const char* s) {
  std::vector<double> v;
  std::stringstream in(s);
  std::string item;
  while (std::getline(in, item, ',')) v.push_back(std::stod(item));
  return v;
}

bool ParseArgs(int argc, char** argv, Options* o) {
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto next = [&]() -> const char* {
      if (i + 1 >= argc) {
        std::fprintf(stderr, "integrand_family: %s needs a value\n", a.c_str());
        std::exit(2);
      }
      return argv[++i];
    };
    if (a == "--n") {
      o->n.clear();
      for (double v : ParseList(next())) o->n.push_back(static_cast<uint32_t>(v));
    } else if (a == "--theta") {
      o->theta = ParseList(next());
    } else if (a == "--theta2") {
      o->theta2 = std::stod(next());
    } else if (a == "--seeds") {
      o->seeds = std::stoi(next());
    } else if (a == "--first-seed") {
      o->first_seed = std::stoi(next());
    } else if (a == "--scrambles") {
      o->scrambles = std::stoi(next());
    } else if (a == "--shifts") {
      o->shifts = std::stoi(next());
    } else if (a == "--offsets") {
      o->offsets = std::stoi(next());
    } else if (a == "--shift-seed") {
      o->shift_seed = std::stoull(next());
    } else if (a == "--gaussian-shifts") {
      o->gaussian_shifts = std::stoi(next());
      if (o->gaussian_shifts < 1) {
        std::fprintf(stderr, "integrand_family: --gaussian-shifts must be at least 1\n");
        std::exit(2);
      }
    } else if (a == "--profile") {
      const std::string profile = next();
      if (profile != "current" && profile != "supplement") {
        std::fprintf(stderr, "integrand_family: --profile is current or supplement\n");
        std::exit(2);
      }
      o->supplement = profile == "supplement";
      if (o->supplement) o->opt = SupplementOptimizerOptions();
    } else if (a == "--construction") {
      o->construction = next();
      if (o->construction != "optimized" && o->construction != "lattice" &&
          o->construction != "lattice-start" && o->construction != "warm" && o->construction != "net" &&
          o->construction != "net-start") {
        std::fprintf(stderr, "integrand_family: --construction is optimized, lattice, lattice-start, "
                             "warm, net or net-start\n");
        std::exit(2);
      }
    } else if (a == "--warm-root") {
      o->warm_root = std::stod(next());
    } else if (a == "--warm-iterations") {
      o->warm_iterations = std::stoi(next());
    } else if (a == "--warm-step") {
      o->warm_step = std::stod(next());
    } else if (a == "--warm-zero") {
      o->warm_zero = std::stod(next());
    } else if (a == "--net-radius") {
      o->net.radius_factor = std::stod(next());
    } else if (a == "--net-frequencies") {
      o->net.max_frequencies = std::stoi(next());
    } else if (a == "--net-sweeps") {
      o->net.sweeps = std::stoi(next());
    } else if (a == "--net-smooth") {
      o->net.smooth_weight = std::stod(next());
    } else if (a == "--net-window") {
      o->net.window_deg = std::stod(next());
    } else if (a == "--warm-anneal") {
      o->warm_anneal = std::stod(next());
    } else if (a == "--warm-warmup") {
      o->warm_warmup = std::stod(next());
    } else if (a == "--warm-warmup-max") {
      o->opt.warm_warmup_max_points = static_cast<uint32_t>(std::stoul(next()));
    } else if (a == "--warm-lr-scale") {
      o->warm_lr_scale = std::stod(next());
    } else if (a == "--stratify") {
      o->opt.stratify_axes = std::stoi(next()) != 0;
    } else if (a == "--kl") {
      o->kl = std::stod(next());
    } else if (a == "--kw") {
      o->kw = std::stod(next());
    } else if (a == "--kr") {
      o->kr = std::stod(next());
    } else if (a == "--exact") {
      o->exact = true;
    } else if (a == "--threads") {
      o->threads = std::stoi(next());
    } else if (a == "--p") {
      o->opt.weighting.exponent = std::stod(next());
    } else if (a == "--margin") {
      o->opt.final_margin = std::stod(next());
    } else if (a == "--tolerance") {
      o->opt.engine_tolerance = std::stod(next());
    } else if (a == "--zero") {
      o->opt.zero_radius = std::stod(next());
    } else if (a == "--warmup") {
      o->opt.warmup_fraction = std::stod(next());
    } else if (a == "--wp") {
      o->opt.warmup_weighting.exponent = std::stod(next());
    } else if (a == "--sw-weight") {
      o->opt.sw_weight = std::stod(next());
    } else if (a == "--iterations") {
      o->opt.max_iterations = std::stoi(next());
    } else if (a == "--lr") {
      o->opt.learning_rate = std::stod(next());
    } else if (a == "--cache") {
      o->cache = next();
    } else if (a == "--out") {
      o->out = next();
    } else if (a == "--members") {
      std::stringstream in(next());
      for (std::string item; std::getline(in, item, ',');) o->members.push_back(item);
    } else if (a == "--help" || a == "-h") {
      std::printf(
          "usage: alignset_integrand_family [--n LIST] [--theta LIST] [--theta2 DEG] [--seeds S]\n"
          "  [--scrambles K] [--shifts S] [--offsets M] [--gaussian-shifts G] [--shift-seed S] [--exact]\n"
          "  [--threads T] [--p P]\n"
          "  [--profile current|supplement] [--construction optimized|lattice|lattice-start|net|net-start|warm]\n"
          "  [--warm-root DEG] [--warm-iterations I] [--warm-step DEG] [--warm-lr-scale X] [--warm-warmup F]\n"
          "  [--warm-warmup-max N] [--warm-anneal R] [--warm-zero R] [--first-seed S]\n"
          "  [--net-radius F] [--net-frequencies K] [--net-sweeps S] [--net-window DEG] [--net-smooth W]\n"
          "  [--wp P] [--warmup F] [--stratify 0|1] [--zero R]\n"
          "  [--margin M] [--kl X] [--kw X] [--kr X] [--sw-weight C] [--iterations I] [--lr LR]\n"
          "  [--tolerance T] [--cache DIR] [--out FILE.tsv] [--members NAME,...]\n");
      std::exit(0);
    } else {
      std::fprintf(stderr, "integrand_family: unknown option %s (try --help)\n", a.c_str());
      return false;
    }
  }
  return true;
}

// One family member: a name and the integrands it averages over, each
// under `shifts` Cranley-Patterson shifts (-1: the run's --shifts; 0: the
// set as it is, no shift: the squared error of the one estimate).
struct Member {
  std::string name;
  std::vector<std::unique_ptr<Integrand>> parts;
  int shifts = -1;
};

// A smooth function that is not periodic on the square, for the members an
// established test suite integrates without a shift; only values and the
// integral are needed (no exact Eq. 18 for these members).
class SmoothNonPeriodic : public Integrand {
 public:
  SmoothNonPeriodic(std::string name, std::function<double(const Point2&)> f)
      : name_(std::move(name)), f_(std::move(f)) {
    // 64 x 64 Gauss-Legendre nodes: exact to rounding for these functions
    // (Gaussians of sigma >= 0.1, polynomials of low degree).
    static const std::vector<std::pair<double, double>> rule = GaussLegendre(64);
    for (const auto& [x, wx] : rule)
      for (const auto& [y, wy] : rule) integral_ += wx * wy * f_({x, y});
  }
  std::string name() const override { return name_; }
  double Value(const Point2& p) const override { return f_(p); }
  double Integral() const override { return integral_; }
  double SquareIntegral() const override { return NAN; }
  std::complex<double> Fourier(int, int) const override { return NAN; }

 private:
  // Nodes and weights on [0, 1] (Newton on the Legendre recurrence).
  static std::vector<std::pair<double, double>> GaussLegendre(int k) {
    std::vector<std::pair<double, double>> out;
    for (int i = 1; i <= k; ++i) {
      double x = std::cos(M_PI * (i - 0.25) / (k + 0.5)), dp = 0.0;
      for (int it = 0; it < 100; ++it) {
        double p0 = 1.0, p1 = x;
        for (int j = 2; j <= k; ++j) {
          const double p2 = ((2.0 * j - 1.0) * x * p1 - (j - 1.0) * p0) / j;
          p0 = p1;
          p1 = p2;
        }
        dp = k * (x * p1 - p0) / (x * x - 1.0);
        const double dx = p1 / dp;
        x -= dx;
        if (std::abs(dx) < 1e-16) break;
      }
      out.push_back({0.5 * (x + 1.0), 1.0 / ((1.0 - x * x) * dp * dp)});
    }
    return out;
  }
  std::string name_;
  std::function<double(const Point2&)> f_;
  double integral_ = 0.0;
};

// The population of anisotropic Gaussians: sigma^2 in [0.01, 1] per axis,
// a random rotation, the centre anywhere in the square; fixed by its seed.
std::vector<std::unique_ptr<Integrand>> RandomGaussians(int count) {
  std::vector<std::unique_ptr<Integrand>> out;
  Pcg32 rng(0x6761757373ULL);
  for (int k = 0; k < count; ++k) {
    const double cx = rng.NextDouble(), cy = rng.NextDouble();
    const double s1 = 0.01 + 0.99 * rng.NextDouble(), s2 = 0.01 + 0.99 * rng.NextDouble();
    const double a = M_PI * rng.NextDouble(), c = std::cos(a), s = std::sin(a);
    const double a11 = c * c / s1 + s * s / s2, a22 = s * s / s1 + c * c / s2;
    const double a12 = c * s * (1.0 / s1 - 1.0 / s2);
    out.push_back(std::make_unique<SmoothNonPeriodic>(
        "gaussian", [=](const Point2& p) {
          const double dx = p.x - cx, dy = p.y - cy;
          return std::exp(-0.5 * (a11 * dx * dx + 2.0 * a12 * dx * dy + a22 * dy * dy));
        }));
  }
  return out;
}

std::vector<Member> Family(double theta, double theta2, int offsets, int gaussian_shifts) {
  auto offset_at = [&](int e) { return offsets == 1 ? 0.0 : 0.5 * (e + 0.5) / offsets - 0.25; };
  std::vector<Member> family;
  auto steps = [&](const std::string& name, double deg) {
    Member m{name, {}};
    for (int e = 0; e < offsets; ++e) m.parts.push_back(StepEdge(deg, offset_at(e)));
    family.push_back(std::move(m));
  };
  auto single = [&](const std::string& name, const std::string& spec) {
    Member m{name, {}};
    m.parts.push_back(std::move(MakeIntegrand(spec)).value());
    family.push_back(std::move(m));
  };
  steps("step theta", theta);
  if (!std::isnan(theta2)) steps("step theta2", theta2);
  steps("step 0", 0.0);
  steps("step 90", 90.0);
  steps("step theta+45", ReduceDirection(theta + 45.0));
  {
    Member m{"smoothstep theta", {}};
    for (int e = 0; e < offsets; ++e) m.parts.push_back(SmoothedStep(theta, 0.1, offset_at(e)));
    family.push_back(std::move(m));
  }
  single("disk", "disk");
  single("triangle", "triangle");
  single("gaussian", "gaussian");
  single("product", "product");
  // Smooth and not periodic on the square: 1024 Gaussians (8 shifts each
  // under CP unless --gaussian-shifts), a linear and a quadratic ramp;
  // without and with shifts.
  for (int shifted = 0; shifted < 2; ++shifted) {
    const std::string how = shifted ? " cp" : " noshift";
    family.push_back({"gaussians" + how, RandomGaussians(1024), shifted ? gaussian_shifts : 0});
    Member ramp{"ramp" + how, {}, shifted ? -1 : 0};
    ramp.parts.push_back(std::make_unique<SmoothNonPeriodic>(
        "ramp", [](const Point2& p) { return p.x + p.y; }));
    family.push_back(std::move(ramp));
    Member quad{"quadratic" + how, {}, shifted ? -1 : 0};
    quad.parts.push_back(std::make_unique<SmoothNonPeriodic>(
        "quadratic", [](const Point2& p) { return p.x * p.x + 0.5 * p.y; }));
    family.push_back(std::move(quad));
  }
  return family;
}

double MemberVariance(const PointSet& points, const Member& m, int shifts, uint64_t shift_seed) {
  if (m.shifts >= 0) shifts = m.shifts;
  double v = 0.0;
  for (const auto& f : m.parts) {
    const Integrand& g = *f;
    if (shifts == 0) {
      double q = 0.0;
      for (const Point2& p : points) q += g.Value(p);
      const double e = q / static_cast<double>(points.size()) - g.Integral();
      v += e * e;
      continue;
    }
    v += CranleyPattersonVariance(
             points, [&](const Point2& p) { return g.Value(p); }, g.Integral(), shifts, shift_seed)
             .variance;
  }
  return v / static_cast<double>(m.parts.size());
}

// Runs fn(i) for i in [0, count) on `threads` threads.
template <typename Fn>
void Parallel(size_t count, int threads, Fn fn) {
  std::atomic<size_t> next{0};
  std::vector<std::thread> pool;
  for (int t = 0; t < std::max(1, threads); ++t) {
    pool.emplace_back([&] {
      for (size_t i; (i = next.fetch_add(1)) < count;) fn(i);
    });
  }
  for (auto& th : pool) th.join();
}

FrequencyParams Params(const Options& o, uint32_t n) {
  const FrequencyParams fp = o.supplement ? SupplementFrequencyParams(n) : DefaultFrequencyParams(n);
  return {fp.length * o.kl, fp.width * o.kw, fp.radius * o.kr};
}

// The options of one warm step: the profile's WarmStartOptions with the
// --warm-* overrides.
OptimizerOptions WarmDescentOptions(const Options& o, uint32_t n) {
  OptimizerOptions opt = WarmStartOptions(o.opt, n, std::isnan(o.theta2) ? 1 : 2);
  if (o.warm_iterations > 0) opt.max_iterations = o.warm_iterations;
  if (o.warm_warmup >= 0) opt.warmup_fraction = o.warm_warmup;
  opt.anneal_ratio = o.warm_anneal;
  if (o.warm_zero >= 0) opt.zero_radius = o.warm_zero;
  if (o.warm_lr_scale > 0.0) opt.learning_rate_scale = o.warm_lr_scale;
  return opt;
}

std::string Key(const Options& o, uint32_t n, double theta, int seed) {
  std::ostringstream s;
  s.precision(17);
  const OptimizerOptions& p = o.opt;
  const FrequencyParams fp = Params(o, n);
  s << "n=" << n << ";t=" << theta << ";t2=" << o.theta2 << ";seed=" << seed
    << ";p=" << p.weighting.exponent << ";sw=" << p.sw_weight << ";it=" << p.max_iterations
    << ";lr=" << p.learning_rate << ";st=" << p.stratify_axes << ";z=" << p.zero_radius
    << ";fm=" << p.final_margin << ";wf=" << p.warmup_fraction
    << ";wp=" << p.warmup_weighting.exponent << ";k=" << fp.length << "," << fp.width << ","
    << fp.radius << ";tol=" << p.engine_tolerance
    // This cache's own version; 7: the pruned FFTs, 8: the faster
    // projection (both: other last bits).
    << ";v=8"
    << (o.construction == "lattice-start" ? ";start=lattice" : "")
    << (o.construction == "net-start" ? ";start=net" : "");
  if (o.construction == "warm") {
    if (o.warm_step != 1.0) s << ";warmstep=" << o.warm_step;
    // The effective first-step scale, so that the sets cached before the
    // profile's two-direction scale existed keep their keys.
    s << ";warm=" << o.warm_root << "," << o.warm_iterations << ","
      << WarmDescentOptions(o, n).learning_rate_scale << ","
      << o.warm_warmup << "," << o.warm_anneal << "," << o.opt.warm_budget_fraction << ","
      << o.opt.warm_warmup_fraction;
    if (o.warm_zero >= 0) s << ",z" << o.warm_zero;
    // Only where it changes the descent, so that the sets cached before the
    // option existed (N at or below it) keep their keys.
    if (n > o.opt.warm_warmup_max_points) s << ",wwmax" << o.opt.warm_warmup_max_points;
  }
  uint64_t h = 0xcbf29ce484222325ULL;
  for (char c : s.str()) h = (h ^ static_cast<unsigned char>(c)) * 0x100000001b3ULL;
  char hex[17];
  std::snprintf(hex, sizeof(hex), "%016llx", static_cast<unsigned long long>(Mix64(h)));
  return hex;
}

bool LoadSet(const std::string& path, uint32_t n, PointSet* out) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return false;
  out->resize(n);
  in.read(reinterpret_cast<char*>(out->data()), n * sizeof(Point2));
  return static_cast<size_t>(in.gcount()) == n * sizeof(Point2);
}

void SaveSet(const std::string& path, const PointSet& p) {
  const std::string tmp = path + ".tmp";
  {
    std::ofstream out(tmp, std::ios::binary);
    out.write(reinterpret_cast<const char*>(p.data()), p.size() * sizeof(Point2));
  }
  std::filesystem::rename(tmp, path);
}

// The aligned set for (n, theta, seed), optimized or from the cache; the
// optimization's wall time goes into *seconds when it ran.
PointSet AlignedSet(const Options& o, uint32_t n, double theta, int seed, double* seconds) {
  if (o.construction == "net") {
    std::vector<double> dirs = {theta};
    if (!std::isnan(o.theta2)) dirs.push_back(o.theta2);
    const auto t0 = std::chrono::steady_clock::now();
    auto net = AlignedNet(n, dirs, static_cast<uint64_t>(seed), o.net);
    *seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (!net.ok()) {
      std::fprintf(stderr, "integrand_family: %s\n", net.status().message().c_str());
      std::exit(1);
    }
    std::printf("# net n=%u theta=%g seed=%d: objective %.3e -> %.3e, %d flips in %d sweeps, %d frequencies, %.2f s\n",
                n, theta, seed, net->start_objective, net->objective, net->flips, net->sweeps, net->frequencies,
                *seconds);
    return std::move(net->points);
  }
  if (o.construction == "lattice") {
    std::vector<double> dirs = {theta};
    if (!std::isnan(o.theta2)) dirs.push_back(o.theta2);
    AlignedLatticeOptions lattice;
    lattice.threads = o.threads;
    const auto t0 = std::chrono::steady_clock::now();
    auto set = AlignedLattice(n, dirs, static_cast<uint64_t>(seed), lattice);
    *seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (!set.ok()) {
      std::fprintf(stderr, "integrand_family: %s\n", set.status().message().c_str());
      std::exit(1);
    }
    return std::move(set).value();
  }
  const std::string path = o.cache + "/set-" + Key(o, n, theta, seed) + ".bin";
  PointSet points;
  if (o.construction == "warm" && std::isnan(o.warm_root)) {
    std::fprintf(stderr, "integrand_family: --construction warm needs --warm-root\n");
    std::exit(2);
  }
  if (o.construction == "warm" && theta == o.warm_root) {
    Options cold = o;
    cold.construction = "optimized";
    return AlignedSet(cold, n, theta, seed, seconds);
  }
  if (LoadSet(path, n, &points)) {
    std::printf("# cached %s\n", path.c_str());
    return points;
  }
  OptimizationProblem problem;
  problem.n = n;
  problem.directions = {theta};
  if (!std::isnan(o.theta2)) problem.directions.push_back(o.theta2);
  problem.seed = static_cast<uint64_t>(seed);
  problem.frequency_params = Params(o, n);
  OptimizerOptions opt = o.opt;
  double parent_seconds = 0.0;
  if (o.construction == "warm") {
    // Steps of warm_step degrees towards the root, the first one shorter
    // when the distance is not a multiple.
    const double distance = std::abs(theta - o.warm_root);
    const double size = o.warm_step <= 0.0 || o.warm_step >= distance
                            ? distance
                            : distance - o.warm_step * std::ceil(distance / o.warm_step - 1.0);
    const double step = theta > o.warm_root ? size : -size;
    problem.start = AlignedSet(o, n, theta - step, seed, &parent_seconds);
    opt = WarmDescentOptions(o, n);
  }
  if (o.construction == "net-start") {
    auto start = AlignedNet(n, problem.directions, static_cast<uint64_t>(seed), o.net);
    if (!start.ok()) {
      std::fprintf(stderr, "integrand_family: %s\n", start.status().message().c_str());
      std::exit(1);
    }
    problem.start = std::move(start->points);
  }
  if (o.construction == "lattice-start") {
    auto start = AlignedLattice(n, problem.directions, static_cast<uint64_t>(seed));
    if (!start.ok()) {
      std::fprintf(stderr, "integrand_family: %s\n", start.status().message().c_str());
      std::exit(1);
    }
    problem.start = std::move(start).value();
  }
  FastEngine engine(o.threads);
  const auto t0 = std::chrono::steady_clock::now();
  auto result = Optimize(problem, opt, engine);
  *seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (!result.ok()) {
    std::fprintf(stderr, "integrand_family: %s\n", result.status().message().c_str());
    std::exit(1);
  }
  std::printf("# optimized N=%u theta=%g seed=%d: %d iterations (%s), %d reverts, loss %.4g "
              "(spectrum %.4g, sw %.4g) in %.2f s -> %s\n",
              n, theta, seed, result->iterations, StopReasonName(result->stop_reason).c_str(),
              result->reverts, result->final_loss.total, result->final_loss.spectrum,
              result->final_loss.sw, *seconds, path.c_str());
  SaveSet(path, result->points);
  return result->points;
}

// Owen-Sobol's mean variance over the scrambles, cached per (n, member
// name + theta, shifts, offsets, scrambles).
double OwenSobolVariance(const Options& o, uint32_t n, double theta, const Member& m) {
  std::ostringstream key;
  key << "owen n=" << n << " t=" << theta << " t2=" << o.theta2 << " m=" << m.name
      << " shifts=" << o.shifts << " offsets=" << o.offsets << " scrambles=" << o.scrambles
      << (o.shift_seed != kDefaultShiftSeed ? " shiftseed=" + std::to_string(o.shift_seed) : "");
  const std::string index = o.cache + "/baseline.txt";
  {
    std::ifstream in(index);
    std::string line;
    while (std::getline(in, line)) {
      const size_t tab = line.find('\t');
      if (tab != std::string::npos && line.substr(0, tab) == key.str()) {
        return std::stod(line.substr(tab + 1));
      }
    }
  }
  std::vector<double> v(static_cast<size_t>(o.scrambles));
  Parallel(v.size(), o.threads, [&](size_t s) {
    v[s] = MemberVariance(OwenScrambledSobol(n, 1000 + s), m, o.shifts, o.shift_seed);
  });
  double mean = 0.0;
  for (double x : v) mean += x / static_cast<double>(v.size());
  std::ofstream out(index, std::ios::app);
  char buf[64];
  std::snprintf(buf, sizeof(buf), "%.10e", mean);
  out << key.str() << '\t' << buf << '\n';
  return mean;
}

int Run(const Options& o) {
  std::filesystem::create_directories(o.cache);
  std::FILE* tsv = o.out.empty() ? nullptr : std::fopen(o.out.c_str(), "w");
  if (tsv) std::fprintf(tsv, "theta\tn\tintegrand\taligned\towen_sobol\tratio\n");
  std::printf("# construction %s\n", o.construction.c_str());
  std::printf("# profile %s: weighting p=%g (warm-up p=%g for %g), stratify %d, zero radius %g, "
              "margin %g, K x(%g, %g, %g), sw=%g iterations=%d, engine tolerance %g; %d seed(s), "
              "Owen-Sobol mean of %d scrambles, %d shifts, %d edge offsets\n",
              o.supplement ? "supplement (v2)" : "current", o.opt.weighting.exponent,
              o.opt.warmup_weighting.exponent, o.opt.warmup_fraction, o.opt.stratify_axes ? 1 : 0,
              o.opt.zero_radius, o.opt.final_margin, o.kl, o.kw, o.kr, o.opt.sw_weight,
              o.opt.max_iterations, o.opt.engine_tolerance, o.seeds, o.scrambles, o.shifts, o.offsets);
  double worst_ratio = 0.0;
  for (double theta : o.theta) {
    std::vector<Member> family = Family(theta, o.theta2, o.offsets, o.gaussian_shifts);
    if (!o.members.empty()) {
      for (const std::string& want : o.members) {
        if (std::none_of(family.begin(), family.end(), [&](const Member& m) { return m.name == want; })) {
          std::fprintf(stderr, "integrand_family: no member '%s'\n", want.c_str());
          return 2;
        }
      }
      std::erase_if(family, [&](const Member& m) {
        return std::find(o.members.begin(), o.members.end(), m.name) == o.members.end();
      });
    }
    std::map<std::string, std::vector<double>> aligned_by_member, owen_by_member;
    for (uint32_t n : o.n) {
      std::vector<PointSet> sets;
      double opt_seconds = 0.0;
      for (int s = o.first_seed; s < o.first_seed + o.seeds; ++s) {
        double t = 0.0;
        sets.push_back(AlignedSet(o, n, theta, s, &t));
        opt_seconds += t;
      }
      std::vector<double> aligned(family.size(), 0.0);
      std::vector<std::pair<size_t, size_t>> jobs;
      for (size_t m = 0; m < family.size(); ++m)
        for (size_t s = 0; s < sets.size(); ++s) jobs.push_back({m, s});
      std::vector<double> values(jobs.size());
      Parallel(jobs.size(), o.threads, [&](size_t j) {
        values[j] = MemberVariance(sets[jobs[j].second], family[jobs[j].first], o.shifts,
                                   o.shift_seed);
      });
      for (size_t j = 0; j < jobs.size(); ++j) aligned[jobs[j].first] += values[j] / sets.size();
      std::printf("\ntheta %g%s  N %u%s\n", theta,
                  std::isnan(o.theta2) ? "" : (" + " + std::to_string(o.theta2)).c_str(), n,
                  opt_seconds > 0 ? (" (optimized in " + std::to_string(opt_seconds) + " s)").c_str()
                                  : "");
      std::printf("  %-16s %12s %12s %8s%s\n", "integrand", "aligned", "owen-sobol", "ratio",
                  o.exact ? "   exact(aligned)  exact(owen) tail%" : "");
      // The exact figures average over the very sets the Monte Carlo columns average over
      // (every seed; the same Owen-Sobol scrambles), so the two columns estimate one number.
      std::vector<DiskSpectrum> spectra_aligned, spectra_owen;
      if (o.exact) {
        FastEngine engine(o.threads);
        for (const PointSet& set : sets) {
          spectra_aligned.push_back(ComputeDiskSpectrum(set, 256, engine));
        }
        for (int s = 0; s < o.scrambles; ++s) {
          spectra_owen.push_back(ComputeDiskSpectrum(OwenScrambledSobol(n, 1000 + s), 256, engine));
        }
      }
      for (size_t m = 0; m < family.size(); ++m) {
        const double owen = OwenSobolVariance(o, n, theta, family[m]);
        const double ratio = aligned[m] / owen;
        worst_ratio = std::max(worst_ratio, ratio);
        aligned_by_member[family[m].name].push_back(aligned[m]);
        owen_by_member[family[m].name].push_back(owen);
        std::printf("  %-16s %12.4e %12.4e %8.3f", family[m].name.c_str(), aligned[m], owen,
                    ratio);
        if (o.exact && family[m].parts.size() == 1) {
          const IntegrandEnergy energy = ComputeIntegrandEnergy(256, *family[m].parts[0]);
          double ea = 0.0, tail = 0.0, eo = 0.0;
          for (const DiskSpectrum& sp : spectra_aligned) {
            const ExactVariance e = ExactCpVariance(sp, energy);
            ea += e.variance / spectra_aligned.size();
            tail += e.tail_estimate / spectra_aligned.size();
          }
          for (const DiskSpectrum& sp : spectra_owen) {
            eo += ExactCpVariance(sp, energy).variance / spectra_owen.size();
          }
          std::printf("   %12.4e %12.4e %5.1f", ea, eo, 100.0 * tail / ea);
        }
        std::printf("\n");
        if (tsv) {
          std::fprintf(tsv, "%g\t%u\t%s\t%.6e\t%.6e\t%.4f\n", theta, n, family[m].name.c_str(),
                       aligned[m], owen, ratio);
        }
      }
    }
    if (o.n.size() >= 2) {
      std::vector<double> ns(o.n.begin(), o.n.end());
      std::printf("\n  slopes over N (theta %g): %-16s %8s %8s\n", theta, "integrand", "aligned",
                  "owen");
      for (const Member& m : family) {
        std::printf("  %37s %8.2f %8.2f\n", m.name.c_str(),
                    LogLogSlope(ns, aligned_by_member[m.name]),
                    LogLogSlope(ns, owen_by_member[m.name]));
      }
    }
  }
  std::printf("\nworst ratio %.3f\n", worst_ratio);
  if (tsv) std::fclose(tsv);
  return 0;
}

}  // namespace
}  // namespace alignset

int main(int argc, char** argv) {
  alignset::Options o;
  if (!alignset::ParseArgs(argc, argv, &o)) return 2;
  return alignset::Run(o);
}

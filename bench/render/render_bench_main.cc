// The rendered proof (docs/rendering.md, "Rendered proof"): renders both scenes with
// every sampler at every N against a running alignset-server and writes the
// measurements bench/render/plot_render.py turns into figures and tables.
// bench/render/run.sh starts its own server and runs both.
//
//   render_bench --server ADDR --out DIR [--size 128] [--n 16,32,...,4096]
//                [--image-n 256,1024,4096] [--scenes antialias,shadow]
//                [--samplers a,b,...] [--threads 2] [--seed 1] [--prepass edges256]
//                [--alt-prepass samples256]
//                [--compare-prepass grid16,grid16c40,grid16c60,jgrid16,samples64,samples1024]
//                [--line-rates 1|0] [--two-max-n 65536]
//
// --prepass is the estimator of record behind `aligned` (core/analysis's
// EstimateDirection on that pre-pass, bench/render/spectral_estimator.h);
// --alt-prepass renders `aligned` with other pre-passes too (variants
// aligned-<prepass>); --compare-prepass adds pre-passes to directions.txt
// only (accuracy and cost against the geometry, no renders).
//
// Two-direction sets are used up to --two-max-n (default: every N; run.sh
// passes 2048). Each N needs about 390 distinct two-direction keys for these
// scenes, the geometry's pairs and the estimator's (about 20 minutes at
// N = 2048 on two cores, once: the server caches them); above the limit a
// pixel with two edges gets the stronger edge's one-direction set.
//
// Writes DIR/render_errors.csv (one row per scene, sampler and N: MSE over
// pixel subsets, the blur criterion, seconds), DIR/tile_blur.csv (the
// screen-space tile's blur criterion on test integrands), DIR/directions.txt
// (the estimator against the geometry), DIR/line_rates.csv (line and segment
// samples on clean straight edges, against the rates of Singh, Miller and
// Jarosz), and .npy images under
// DIR/images.
#include <filesystem>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "render/direction.h"
#include "render/lattice_sets.h"
#include "render/pixel_samplers.h"
#include "render/pixel_shape.h"
#include "render/renderer.h"
#include "render/scene.h"
#include "render/set_fetch.h"
#include "render/spectral_estimator.h"
#include "cli/progress.h"
#include <alignset/client.h>
#include <alignset/npy.h>
#include "core/sampling/screen_space_rank1.h"
#include "core/sampling/owen_sobol.h"
#include "core/util/angles.h"
#include "core/util/hash.h"

namespace alignset::render {
namespace {

std::vector<std::string> Split(const std::string& s) {
  std::vector<std::string> out;
  std::stringstream ss(s);
  for (std::string item; std::getline(ss, item, ',');) {
    if (!item.empty()) out.push_back(item);
  }
  return out;
}

double Seconds(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// A bench variant: a sampler name of MakePixelSampler plus its options.
struct Variant {
  std::string label;
  std::string sampler;
  AlignedPolicy policy;
  LineOrientation orientation = LineOrientation::kNormal;
  bool per_pixel_shift = true;
  std::string prepass;  // aligned: the estimator's pre-pass (empty: the one of record)
  bool reuse = false;   // the pre-pass folded into the estimate (render/prepass_reuse.h)
  bool continued = true;  // with reuse: direction-less pixels continue the pre-pass's sequence
};

// A variant with the default options.
Variant Named(std::string label, std::string sampler) {
  Variant v;
  v.label = std::move(label);
  v.sampler = std::move(sampler);
  return v;
}

bool IsLattice(const Variant& v) { return v.sampler.rfind("aligned-lattice", 0) == 0; }
bool IsTentLattice(const Variant& v) { return v.sampler.rfind("aligned-tent-lattice", 0) == 0; }

std::vector<Variant> AllVariants() {
  std::vector<Variant> v;
  for (const char* s : {"random", "owen-sobol", "pmj02bn", "pmj02bn-sheared", "rank1-lattice",
                        "screen-space-rank1", "aligned", "aligned-exact", "aligned-lattice",
                        "aligned-lattice-exact", "aligned-tent-lattice", "aligned-tent-lattice-exact"}) {
    v.push_back(Named(s, s));
  }
  // Every sample counted and used: the estimated samplers with their
  // (randomized) pre-pass folded in; labels end in "+reuse" (the renderer's
  // default) or "+unbiased" (count weights on direction-less pixels too).
  for (const char* s : {"aligned", "aligned-lattice", "aligned-tent-lattice", "pmj02bn-sheared"}) {
    Variant r = Named(std::string(s) + "+reuse", s);
    r.reuse = true;
    v.push_back(r);
  }
  Variant unbiased = Named("aligned-lattice+unbiased", "aligned-lattice");
  unbiased.reuse = true;
  unbiased.continued = false;
  v.push_back(unbiased);
  Variant axis = Named("aligned-none-axis", "aligned");
  axis.policy.none = AlignedPolicy::None::kAxisSet;
  v.push_back(axis);
  Variant one_dir = Named("aligned-exact-1dir", "aligned-exact");
  one_dir.policy.two_directions = false;
  v.push_back(one_dir);
  Variant same_shift = Named("aligned-exact-noshift", "aligned-exact");
  same_shift.per_pixel_shift = false;
  v.push_back(same_shift);
  for (const char* kind : {"line", "segment"}) {
    for (auto [o, name] : {std::pair{LineOrientation::kNormal, "normal"},
                           std::pair{LineOrientation::kEdge, "edge"},
                           std::pair{LineOrientation::kRandom, "random"}}) {
      Variant l = Named(std::string(kind) + "-" + name, kind);
      l.orientation = o;
      v.push_back(l);
    }
  }
  return v;
}

// Pixel subsets the errors are reported over (columns of render_errors.csv).
struct Subsets {
  std::vector<std::string> names;
  std::vector<std::vector<size_t>> pixels;
};

Subsets MakeSubsets(const Scene& scene, const std::vector<PixelDirection>& exact,
                    const std::vector<PixelDirection>& estimated) {
  Subsets s;
  s.names = {"edge", "smooth", "edge_one", "edge_two", "edge_est_none", "smooth_est_none",
             "smooth_est_dir"};
  // The edge pixels by type (render/pixel_shape.h): edge_straight, ...
  const std::vector<PixelShape> types = {PixelShape::kStraight, PixelShape::kParallel,
                                         PixelShape::kCurved, PixelShape::kCorner};
  for (PixelShape t : types) s.names.push_back("edge_" + ShapeName(t));
  s.pixels.resize(s.names.size());
  const std::vector<PixelClass> classes = scene.Classes();
  for (size_t i = 0; i < classes.size(); ++i) {
    const PixelShape shape = ClassifyShape(scene.Pixel(i));
    for (size_t t = 0; t < types.size(); ++t) {
      if (shape == types[t]) s.pixels[7 + t].push_back(i);
    }
    const bool edge = classes[i] == PixelClass::kEdge, smooth = classes[i] == PixelClass::kSmooth;
    const bool est_none = estimated[i].kind == PixelDirection::Kind::kNone;
    if (edge) s.pixels[0].push_back(i);
    if (smooth) s.pixels[1].push_back(i);
    if (edge && exact[i].kind == PixelDirection::Kind::kOne) s.pixels[2].push_back(i);
    if (edge && exact[i].kind == PixelDirection::Kind::kTwo) s.pixels[3].push_back(i);
    if (edge && est_none) s.pixels[4].push_back(i);
    if (smooth && est_none) s.pixels[5].push_back(i);
    if (smooth && !est_none) s.pixels[6].push_back(i);
  }
  return s;
}

double SubsetMse(const std::vector<double>& img, const std::vector<double>& ref,
                 const std::vector<size_t>& pixels) {
  if (pixels.empty()) return std::nan("");
  double s = 0.0;
  for (size_t i : pixels) s += (img[i] - ref[i]) * (img[i] - ref[i]);
  return s / static_cast<double>(pixels.size());
}

struct SceneData {
  Scene scene;
  std::vector<double> reference;
  std::vector<PixelClass> classes;
  std::vector<PixelDirection> exact, estimated;
  std::map<std::string, std::vector<PixelDirection>> by_prepass;  // every pre-pass estimated
  Subsets subsets;
  double estimate_seconds = 0.0;
};

// The estimator against the geometry on one scene: angle errors where both
// see one direction, and the kinds each sees.
void DirectionReport(std::ofstream& out, const SceneData& d, const std::vector<PixelDirection>& est,
                     const DirectionEstimator& e, double seconds, int64_t refusals, bool of_record) {
  std::vector<double> errors, errors_two;
  int confusion[3][3] = {};
  for (size_t i = 0; i < d.classes.size(); ++i) {
    if (d.classes[i] == PixelClass::kConstant) continue;
    confusion[int(d.exact[i].kind)][int(est[i].kind)]++;
    if (d.exact[i].kind == PixelDirection::Kind::kOne && est[i].kind != PixelDirection::Kind::kNone) {
      errors.push_back(AxialDistanceDeg(d.exact[i].theta1, est[i].theta1));
    }
    if (d.exact[i].kind == PixelDirection::Kind::kTwo && est[i].kind != PixelDirection::Kind::kNone) {
      // The estimate's first direction against the nearer of the two.
      errors_two.push_back(std::min(AxialDistanceDeg(d.exact[i].theta1, est[i].theta1),
                                    AxialDistanceDeg(d.exact[i].theta2, est[i].theta1)));
    }
  }
  std::sort(errors.begin(), errors.end());
  std::sort(errors_two.begin(), errors_two.end());
  auto q = [](const std::vector<double>& v, double p) {
    return v.empty() ? NAN : v[size_t(p * (v.size() - 1))];
  };
  out << "scene " << d.scene.name() << ": estimator " << e.name() << (of_record ? " [aligned]" : "")
      << ", " << e.evaluations() << " integrand evaluations per pixel, " << seconds << " s for "
      << d.scene.size() << " pixels, " << refusals << " pre-passes refused\n";
  out << "  angle error on one-direction edge pixels (deg): median " << q(errors, 0.5) << ", p90 "
      << q(errors, 0.9) << ", p99 " << q(errors, 0.99) << " (" << errors.size() << " pixels)\n";
  out << "  first direction against the nearer edge on two-direction edge pixels (deg): median "
      << q(errors_two, 0.5) << ", p90 " << q(errors_two, 0.9) << " (" << errors_two.size()
      << " pixels)\n";
  out << "  kinds, rows = geometry (none, one, two), columns = estimator (none, one, two), non-constant pixels:\n";
  for (int r = 0; r < 3; ++r) {
    out << "   ";
    for (int c = 0; c < 3; ++c) out << " " << confusion[r][c];
    out << "\n";
  }
}

// Singh, Miller and Jarosz's predictions on clean straight edges: 256 pixels, each a step
// with a random normal and offset; variance of points (Owen-Sobol) and of
// line and segment samples across, along and at random to the edge.
void LineRates(const std::string& path, const std::vector<uint32_t>& ns) {
  Pcg32 rng(404);
  struct Edge {
    PixelIntegrand f;
    double normal;
  };
  std::vector<Edge> edges;
  for (int k = 0; k < 256; ++k) {
    const double deg = 180.0 * rng.NextDouble();
    const V2 nn = {std::cos(DegToRad(deg)), std::sin(DegToRad(deg))};
    const V2 c = {0.25 + 0.5 * rng.NextDouble(), 0.25 + 0.5 * rng.NextDouble()};
    const Polygon half = ClipHalfPlane({{0, 0}, {1, 0}, {1, 1}, {0, 1}}, nn, Dot(nn, c));
    edges.push_back({PixelIntegrand(Linear{0.2, 0, 0}, {Fragment{half, Linear{0.9, 0, 0}, {}}}), deg});
  }
  std::ofstream out(path);
  out << "n,estimator,mse\n";
  constexpr int kReps = 8;
  for (uint32_t n : ns) {
    std::map<std::string, double> mse;
    for (size_t k = 0; k < edges.size(); ++k) {
      const Edge& e = edges[k];
      for (int r = 0; r < kReps; ++r) {
        const uint64_t h = HashCombine(HashCombine(n, k), r);
        const double random_deg = 180.0 * HashShift(Mix64(h)).x;
        auto add = [&](const std::string& name, double v) {
          mse[name] += (v - e.f.Exact()) * (v - e.f.Exact()) / (kReps * edges.size());
        };
        double pts = 0.0;
        for (const Point2& p : OwenScrambledSobol(n, h)) pts += e.f.Eval({p.x, p.y});
        add("points-owen-sobol", pts / n);
        add("line-normal", LineEstimate(e.f, n, e.normal, h));
        add("line-edge", LineEstimate(e.f, n, e.normal + 90.0, h));
        add("line-random", LineEstimate(e.f, n, random_deg, h));
        add("segment-normal", SegmentEstimate(e.f, n, e.normal, 0.5, h));
        add("segment-edge", SegmentEstimate(e.f, n, e.normal + 90.0, 0.5, h));
        add("segment-random", SegmentEstimate(e.f, n, random_deg, 0.5, h));
      }
    }
    for (const auto& [name, v] : mse) out << n << "," << name << "," << v << "\n";
    out.flush();
    std::fprintf(stderr, "line rates N=%u done\n", n);
  }
}

int Main(int argc, char** argv) {
  std::map<std::string, std::string> a = {
      {"server", ""}, {"out", "bench/results/render"}, {"size", "128"},
      {"n", "16,32,64,128,256,512,1024,2048,4096"}, {"image-n", "256,1024,4096"},
      {"scenes", "antialias,shadow"}, {"samplers", ""}, {"threads", "2"}, {"seed", "1"},
      {"prepass", kDefaultPrepass}, {"alt-prepass", "samples256"},
      {"compare-prepass", "grid16,grid16c40,grid16c60,jgrid16,samples64,samples1024"},
      {"line-rates", "1"}, {"two-max-n", "65536"}, {"lattice-window", "1"}, {"tent-window", "2"},
      {"lattice-size-span", "0"}};
  for (int i = 1; i < argc; ++i) {
    std::string k = argv[i];
    if (k.rfind("--", 0) != 0 || i + 1 >= argc || !a.count(k.substr(2))) {
      std::fprintf(stderr, "render_bench: unknown or incomplete option '%s'\n", argv[i]);
      return 2;
    }
    a[k.substr(2)] = argv[++i];
  }
  if (a["server"].empty()) {
    std::fprintf(stderr, "render_bench: --server ADDR is required (bench/render/run.sh starts one)\n");
    return 2;
  }
  // Degrees either side of a pixel's θ its lattice is chosen for:
  // aligned-lattice* (`alignset render --lattice-window`) and
  // aligned-tent-lattice* (--tent-window); nullopt after the error message.
  auto window = [&a](const std::string& flag) -> std::optional<double> {
    const double w = std::strtod(a[flag].c_str(), nullptr);
    if (w >= 0.0 && w <= 10.0) return w;
    std::fprintf(stderr, "render_bench: --%s must be in [0, 10] degrees, got %s\n", flag.c_str(),
                 a[flag].c_str());
    return std::nullopt;
  };
  const std::optional<double> lattice_window_flag = window("lattice-window");
  const std::optional<double> tent_window_flag = window("tent-window");
  if (!lattice_window_flag || !tent_window_flag) return 2;
  const double lattice_window = *lattice_window_flag, tent_window = *tent_window_flag;
  // aligned-lattice*: each key's lattice may have N - span ... N points, the
  // size that scores best (render/lattice_sets.h).
  char* span_end = nullptr;
  const long size_span = std::strtol(a["lattice-size-span"].c_str(), &span_end, 10);
  if (span_end == a["lattice-size-span"].c_str() || *span_end != '\0' || size_span < 0 || size_span > 1024) {
    std::fprintf(stderr, "render_bench: --lattice-size-span must be in [0, 1024], got %s\n",
                 a["lattice-size-span"].c_str());
    return 2;
  }
  const std::string out = a["out"];
  // The whole path (a run under a new parent folder once lost its tables
  // silently); a folder that cannot be made stops the run here.
  std::error_code made;
  std::filesystem::create_directories(out + "/images", made);
  if (made) {
    std::fprintf(stderr, "render_bench: cannot create %s/images: %s\n", out.c_str(), made.message().c_str());
    return 1;
  }
  const int size = std::atoi(a["size"].c_str()), threads = std::atoi(a["threads"].c_str());
  const uint64_t seed = std::strtoull(a["seed"].c_str(), nullptr, 10);
  std::vector<uint32_t> ns, image_ns;
  for (const std::string& s : Split(a["n"])) ns.push_back(std::strtoul(s.c_str(), nullptr, 10));
  for (const std::string& s : Split(a["image-n"])) image_ns.push_back(std::strtoul(s.c_str(), nullptr, 10));
  std::vector<Variant> variants;
  const std::vector<std::string> wanted = Split(a["samplers"]);
  for (const Variant& v : AllVariants()) {
    if (wanted.empty() || std::find(wanted.begin(), wanted.end(), v.label) != wanted.end()) {
      variants.push_back(v);
    }
  }

  // Checked before any work starts; a --prepass that does not parse is
  // refused below with its reason.
  if (auto record = ParsePrepass(a["prepass"]); record.ok() && !record->Reusable()) {
    for (const Variant& v : variants) {
      if (!v.reuse) continue;
      std::fprintf(stderr, "render_bench: %s needs a reusable --prepass (samplesM or edgesM), got %s\n",
                   v.label.c_str(), a["prepass"].c_str());
      return 2;
    }
  }

  ConnectOptions opts;
  opts.address = a["server"];
  auto client = ServiceClient::Connect(opts);
  if (!client.ok()) {
    std::fprintf(stderr, "render_bench: %s\n", client.status().message().c_str());
    return 1;
  }

  if (a["line-rates"] == "1") LineRates(out + "/line_rates.csv", ns);

  std::vector<Prepass> prepasses;
  for (const std::string& spec :
       Split(a["prepass"] + "," + a["alt-prepass"] + "," + a["compare-prepass"])) {
    auto p = ParsePrepass(spec);
    if (!p.ok()) {
      std::fprintf(stderr, "render_bench: %s\n", p.status().message().c_str());
      return 2;
    }
    bool seen = false;
    for (const Prepass& q : prepasses) seen |= q.Name() == p->Name();
    if (!seen) prepasses.push_back(*p);
  }
  for (const std::string& spec : Split(a["alt-prepass"])) {
    const std::string name = ParsePrepass(spec)->Name();
    if (name == prepasses.front().Name()) continue;
    Variant alt = Named("aligned-" + name, "aligned");
    alt.prepass = name;
    if (wanted.empty() || std::find(wanted.begin(), wanted.end(), alt.label) != wanted.end()) {
      variants.push_back(alt);
    }
  }
  std::vector<SceneData> scenes;
  std::ofstream dir_out(out + "/directions.txt");
  std::ofstream est_csv(out + "/estimator.csv");  // the estimator of record's cost, per scene
  est_csv << "scene,prepass,evaluations,seconds,pixels,threads\n";
  for (const std::string& name : Split(a["scenes"])) {
    auto t0 = std::chrono::steady_clock::now();
    auto scene = MakeScene(name, size, size, seed);
    if (!scene.ok()) {
      std::fprintf(stderr, "render_bench: %s\n", scene.status().message().c_str());
      return 2;
    }
    SceneData d;
    d.scene = std::move(*scene);
    d.reference = d.scene.Reference();
    d.classes = d.scene.Classes();
    d.exact = GeometryDirections(d.scene);
    // One estimate per pre-pass without its confidence floor (the costly
    // part, timed), then each floor applied to it.
    struct Raw {
      std::vector<PixelDirection> directions;
      double seconds = 0.0;
      int64_t refusals = 0;
    };
    std::map<std::string, Raw> raw;
    for (size_t k = 0; k < prepasses.size(); ++k) {
      Prepass unfloored = prepasses[k];
      unfloored.min_confidence_pct = 0;
      const std::unique_ptr<DirectionEstimator> estimator = MakeSpectralEstimator(unfloored);
      auto it = raw.find(unfloored.Name());
      if (it == raw.end()) {
        auto te = std::chrono::steady_clock::now();
        std::vector<PixelDirection> est = EstimateDirections(d.scene, *estimator, seed, threads);
        it = raw.emplace(unfloored.Name(), Raw{std::move(est), Seconds(te), estimator->refusals()}).first;
        std::fprintf(stderr, "scene %s: directions by %s in %.1f s\n", name.c_str(),
                     estimator->name().c_str(), it->second.seconds);
      }
      std::vector<PixelDirection> est = it->second.directions;
      for (PixelDirection& p : est) p = ApplyConfidenceFloor(p, prepasses[k].min_confidence_pct);
      const double secs = it->second.seconds;
      const auto named = MakeSpectralEstimator(prepasses[k]);
      DirectionReport(dir_out, d, est, *named, secs, it->second.refusals, k == 0);
      dir_out.flush();
      if (k > 0) d.by_prepass[prepasses[k].Name()] = est;
      if (k == 0) {
        est_csv << name << "," << prepasses[k].Name() << "," << named->evaluations() << ","
                << secs << "," << d.scene.size() << "," << threads << "\n";
        d.estimated = std::move(est);
        d.estimate_seconds = secs;
      }
    }
    d.subsets = MakeSubsets(d.scene, d.exact, d.estimated);
    const std::vector<size_t> shape = {size_t(size), size_t(size)};
    std::vector<double> cls, t_exact, t_est, k_exact, k_est;
    for (size_t i = 0; i < d.classes.size(); ++i) {
      cls.push_back(double(d.classes[i]));
      k_exact.push_back(double(d.exact[i].kind));
      k_est.push_back(double(d.estimated[i].kind));
      t_exact.push_back(d.exact[i].theta1);
      t_est.push_back(d.estimated[i].theta1);
    }
    WriteNpy(out + "/images/" + name + "_reference.npy", shape, d.reference);
    WriteNpy(out + "/images/" + name + "_classes.npy", shape, cls);
    std::vector<double> shapes;
    for (size_t i = 0; i < d.scene.size(); ++i) shapes.push_back(double(ClassifyShape(d.scene.Pixel(i))));
    WriteNpy(out + "/images/" + name + "_shapes.npy", shape, shapes);
    WriteNpy(out + "/images/" + name + "_theta_exact.npy", shape, t_exact);
    WriteNpy(out + "/images/" + name + "_theta_estimated.npy", shape, t_est);
    WriteNpy(out + "/images/" + name + "_kind_exact.npy", shape, k_exact);
    WriteNpy(out + "/images/" + name + "_kind_estimated.npy", shape, k_est);
    std::fprintf(stderr, "scene %s: %zu edge, %zu smooth pixels; built and estimated in %.1f s\n",
                 name.c_str(), d.subsets.pixels[0].size(), d.subsets.pixels[1].size(), Seconds(t0));
    scenes.push_back(std::move(d));
  }
  dir_out.close();
  est_csv.close();

  const std::vector<double> sigmas = {1.0, 2.0, 4.0};
  std::ofstream csv(out + "/render_errors.csv");
  csv << "scene,sampler,n,mse_all";
  for (const std::string& s : scenes.front().subsets.names) csv << ",mse_" << s;
  for (double s : sigmas) csv << ",blur_rms_" << s;
  csv << ",seconds\n";
  std::ofstream tile_csv(out + "/tile_blur.csv");
  tile_csv << "n,sigma,optimized,random,seconds\n";

  const uint32_t two_max_n = std::strtoul(a["two-max-n"].c_str(), nullptr, 10);
  for (uint32_t n : ns) {
    // Above two_max_n the two-direction variants fall back to one direction,
    // so the *-1dir ablation would repeat its parent.
    std::vector<Variant> now;
    for (Variant v : variants) {
      if (n > two_max_n) {
        if (v.label == "aligned-exact-1dir") continue;
        v.policy.two_directions = false;
      }
      now.push_back(v);
    }
    // The sets every scene's aligned variants will read.
    std::set<std::pair<int, int>> pairs;
    for (const SceneData& d : scenes) {
      for (const Variant& v : now) {
        if (v.sampler != "aligned" && v.sampler != "aligned-exact") continue;
        const auto& dirs = v.sampler == "aligned-exact" ? d.exact
                           : v.prepass.empty()          ? d.estimated
                                                        : d.by_prepass.at(v.prepass);
        for (const auto& p : NeededPairs(dirs, v.policy)) pairs.insert(p);
      }
    }
    RenderSets table;
    bool need_sets = false;
    for (const Variant& v : variants) {
      need_sets |= v.sampler.rfind("aligned", 0) == 0 && !IsLattice(v);
    }
    if (need_sets) {
      std::map<std::string, std::unique_ptr<cli::Progress>> bars;
      auto t0 = std::chrono::steady_clock::now();
      auto fetched = FetchAlignedSets(**client, n, pairs,
                                      [&](const std::string& stage, double done, double total,
                                          const std::string& detail) {
                                        auto& bar = bars[stage];
                                        if (!bar) bar = std::make_unique<cli::Progress>(stage);
                                        bar->Update(done, total, detail);
                                      });
      for (auto& [stage, bar] : bars) bar->Finish("");
      if (!fetched.ok()) {
        std::fprintf(stderr, "render_bench: N=%u: %s\n", n, fetched.status().message().c_str());
        return 1;
      }
      table = std::move(*fetched);
      std::fprintf(stderr, "N=%u: 46 one-direction keys and %zu pair keys (for %zu pairs) in %.1f s\n", n,
                   PairKeys(pairs).size(), pairs.size(), Seconds(t0));
    }
    // The aligned lattices (and the tent-folded ones), chosen here for the
    // served degrees and pairs the lattice variants' direction maps need (no
    // server).
    RenderSets lattices, tents;
    for (const bool folded : {false, true}) {
      std::vector<const std::vector<PixelDirection>*> maps;
      AlignedPolicy policy;
      for (const SceneData& d : scenes) {
        for (const Variant& v : now) {
          if (!(folded ? IsTentLattice(v) : IsLattice(v))) continue;
          maps.push_back(v.sampler.ends_with("-exact") ? &d.exact : &d.estimated);
          policy = v.policy;
        }
      }
      if (maps.empty()) continue;
      LatticeTableStats st;
      cli::Progress bar(folded ? "tent lattices" : "lattices");
      auto built = AlignedLatticeTable(n, maps, policy, folded ? tent_window : lattice_window, threads, &st,
                                       [&](double done, double total) { bar.Update(done, total, ""); }, folded,
                                       folded ? 0 : static_cast<uint32_t>(size_span));
      bar.Finish("");
      if (!built.ok()) {
        std::fprintf(stderr, "render_bench: N=%u: %s\n", n, built.status().message().c_str());
        return 1;
      }
      (folded ? tents : lattices) = std::move(*built);
      std::fprintf(stderr,
                   "N=%u: %zu one-direction and %zu two-direction %slattices (%zu searches; %zu keys below N, "
                   "%.1f points a key) in %.1f s\n",
                   n, st.one, st.two, folded ? "tent-folded " : "", st.searched, st.smaller, st.mean_points,
                   st.seconds);
    }
    ShiftTile tile;
    bool need_tile = false;
    for (const Variant& v : variants) need_tile |= v.sampler == "screen-space-rank1";
    if (need_tile) {
      auto t0 = std::chrono::steady_clock::now();
      ShiftTileOptions o;  // 64 x 64 tile, 128 test integrands, sigma 1
      tile = *OptimizeShiftTile(n, o);
      const double secs = Seconds(t0);
      const ShiftTile random = RandomShiftTile(o.size, o.seed);
      for (double s : {0.0, 1.0, 2.0, 4.0}) {
        tile_csv << n << "," << s << "," << TileBlurCriterion(n, tile, s, 64, 4242) << ","
                 << TileBlurCriterion(n, random, s, 64, 4242) << "," << secs << "\n";
      }
      tile_csv.flush();
    }
    for (const SceneData& d : scenes) {
      for (const Variant& v : now) {
        SamplerConfig c;
        c.name = v.sampler;
        c.n = n;
        c.estimated = v.prepass.empty() ? &d.estimated : &d.by_prepass.at(v.prepass);
        c.exact = &d.exact;
        c.sets = IsTentLattice(v) ? &tents : IsLattice(v) ? &lattices : &table;
        c.policy = v.policy;
        c.per_pixel_shift = v.per_pixel_shift;
        c.reuse_prepass = v.reuse;
        c.continue_prepass = v.continued;
        c.tile = &tile;
        c.orientation = v.orientation;
        auto sampler = MakePixelSampler(c);
        if (!sampler.ok()) {
          std::fprintf(stderr, "render_bench: %s N=%u: %s\n", v.label.c_str(), n,
                       sampler.status().message().c_str());
          return 1;
        }
        auto t0 = std::chrono::steady_clock::now();
        const std::vector<double> img = Render(d.scene, **sampler, seed, threads);
        const double secs = Seconds(t0);
        for (double x : img) {
          if (!std::isfinite(x)) {
            std::fprintf(stderr, "render_bench: %s N=%u gave a non-finite pixel\n", v.label.c_str(), n);
            return 1;
          }
        }
        const ImageErrors e = MeasureErrors(img, d.reference, d.classes, d.scene.width(),
                                            d.scene.height(), sigmas);
        csv << d.scene.name() << "," << v.label << "," << n << "," << e.mse_all;
        for (const auto& px : d.subsets.pixels) csv << "," << SubsetMse(img, d.reference, px);
        for (double b : e.blur_rms) csv << "," << b;
        csv << "," << secs << "\n";
        csv.flush();
        // The image-N grids, and every N >= 256 of the samplers the
        // acceptance table compares (plot_render.py bootstraps its ratios
        // over their edge pixels; pixel_split.py splits them by pixel type
        // and by what the estimate made of the pixel).
        const bool compared =
            n >= 256 && (v.sampler == "aligned" || v.label == "aligned-exact" ||
                         v.sampler == "aligned-lattice" || v.label == "aligned-lattice-exact" ||
                         v.sampler == "aligned-tent-lattice" || v.label == "aligned-tent-lattice-exact" ||
                         v.label == "rank1-lattice" || v.label == "screen-space-rank1" ||
                         v.label == "pmj02bn" || v.label == "owen-sobol" || v.label == "pmj02bn-sheared");
        if (compared || std::find(image_ns.begin(), image_ns.end(), n) != image_ns.end()) {
          WriteNpy(out + "/images/" + d.scene.name() + "_" + v.label + "_n" + std::to_string(n) + ".npy",
                   {size_t(d.scene.height()), size_t(d.scene.width())}, img);
        }
        std::fprintf(stderr, "[%s N=%u] %-22s edge MSE %.3e  smooth MSE %.3e  (%.1f s)\n",
                     d.scene.name().c_str(), n, v.label.c_str(), e.mse_edge, e.mse_smooth, secs);
      }
    }
  }
  return 0;
}

}  // namespace
}  // namespace alignset::render

int main(int argc, char** argv) { return alignset::render::Main(argc, argv); }

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "cli/commands.h"
#include "cli/json_text.h"
#include "cli/plot_script.h"
#include "cli/point_file.h"
#include "core/analysis/expected_spectrum.h"
#include "core/spectral/spectral_engine.h"

namespace alignset::cli {
namespace {

struct AnalyzeOptions {
  std::vector<std::string> files;
  std::vector<double> dirs;
  int64_t max_frequency = 0;
  int64_t bins = 180;
  double r_min = 0.0;
  std::string png;
  std::string title;
  bool json = false;
  std::string engine = "auto";
  int64_t threads = 0;
};

int Usage(const Status& s) { return ReportError("analyze", s, kExitUsage); }
int Failure(const Status& s) { return ReportError("analyze", s, kExitFailure); }

std::string ToJson(const AnalyzeOptions& o, const ExpectedSpectrum& s,
                   const std::vector<double>& radial, const std::vector<double>& dirs,
                   const std::vector<std::vector<double>>& directional,
                   const std::vector<double>& angular, double r_min) {
  std::string j = "{\"kind\":\"spectrum\",\"title\":" + JsonString(o.title) + ",\"files\":[";
  for (size_t i = 0; i < o.files.size(); ++i) j += (i ? "," : "") + JsonString(o.files[i]);
  j += "],\"n\":" + std::to_string(s.point_count) + ",\"sets\":" + std::to_string(s.set_count) +
       ",\"max_frequency\":" + std::to_string(s.max_frequency) + ",\"radial\":" +
       JsonArray(radial) + ",\"directional\":[";
  for (size_t i = 0; i < dirs.size(); ++i) {
    j += std::string(i ? "," : "") + "{\"deg\":" + JsonNumber(dirs[i]) +
         ",\"power\":" + JsonArray(directional[i]) + "}";
  }
  j += "],\"angular\":{\"r_min\":" + JsonNumber(r_min) + ",\"power\":" + JsonArray(angular) +
       "},\"power\":[";
  const int m = s.max_frequency;
  for (int a = -m; a <= m; ++a) {
    std::vector<double> row;
    for (int b = -m; b <= m; ++b) row.push_back(a == 0 && b == 0 ? NAN : s.At(a, b));
    j += (a > -m ? "," : "") + JsonArray(row);
  }
  return j + "]}\n";
}

double MeanOver(const std::vector<double>& p, int lo, int hi) {
  double sum = 0.0;
  int count = 0;
  for (int i = std::max(lo, 1); i <= std::min<int>(hi, static_cast<int>(p.size()) - 1); ++i) {
    if (std::isnan(p[i])) continue;  // no integer frequency on the line there
    sum += p[i];
    ++count;
  }
  return count ? sum / count : NAN;
}

int RunAnalyze(const AnalyzeOptions& o) {
  auto kind = ParseEngineKind(o.engine);
  if (!kind.ok()) return Usage(kind.status());
  std::vector<PointSet> sets;
  for (const std::string& path : o.files) {
    auto read = ReadPointSets(path);
    if (!read.ok()) return Usage(read.status());
    for (PointSet& s : *read) sets.push_back(std::move(s));
  }
  const size_t n = sets[0].size();
  for (size_t i = 0; i < sets.size(); ++i) {
    if (sets[i].size() != n) {
      return Usage(Status::InvalidArgument(
          "the sets have different N (" + std::to_string(n) + " and " +
          std::to_string(sets[i].size()) + "): an expected spectrum averages sets of one N"));
    }
  }
  const int m = o.max_frequency > 0
                    ? static_cast<int>(o.max_frequency)
                    : std::clamp(static_cast<int>(std::lround(2.0 * std::sqrt(double(n)))), 8, 256);
  auto engine = MakeSpectralEngine(*kind, static_cast<int>(o.threads));
  if (!engine.ok()) return Failure(engine.status());
  auto spectrum = ComputeExpectedSpectrum(sets, m, **engine);
  if (!spectrum.ok()) return Usage(spectrum.status());

  std::vector<double> dirs = {0.0, 90.0};
  for (double d : o.dirs) dirs.push_back(d);
  // The angular profile leaves out the lowest radii, where a few integer
  // frequencies would each fill whole degrees of angle.
  const double r_min = o.r_min > 0.0 ? o.r_min : std::max(4.0, 0.125 * m);
  const std::vector<double> radial = RadialProfile(*spectrum);
  std::vector<std::vector<double>> directional;
  for (double d : dirs) directional.push_back(DirectionalProfile(*spectrum, d));
  const std::vector<double> angular = AngularProfile(*spectrum, static_cast<int>(o.bins), r_min);
  const std::string json = ToJson(o, *spectrum, radial, dirs, directional, angular, r_min);

  if (!o.png.empty()) {
    if (Status s = WritePlot(json, o.png); !s.ok()) return Failure(s);
  }
  if (o.json) {
    std::fputs(json.c_str(), stdout);
    return kExitOk;
  }
  std::printf("sets           %d of N = %zu (expected power spectrum: their mean periodogram; "
              "white noise = 1)\n",
              spectrum->set_count, n);
  std::printf("frequencies    |a|, |b| <= %d\n", m);
  std::printf("radial         ");
  for (int r : {1, 2, 4, 8, 16, 32, 64, 128, 256}) {
    if (r <= m) std::printf(" |v|=%d: %.3g", r, radial[r]);
  }
  std::printf("\n");
  const int q = std::max(1, m / 4);
  std::printf("directional    mean power along each direction, |v.d| in [1, %d] and [%d, %d]\n", q,
              q + 1, m);
  for (size_t i = 0; i < dirs.size(); ++i) {
    std::printf("  %7.2f deg   %.3g   %.3g\n", dirs[i], MeanOver(directional[i], 1, q),
                MeanOver(directional[i], q + 1, m));
  }
  std::vector<size_t> order(angular.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](size_t x, size_t y) { return angular[x] < angular[y]; });
  double mean = 0.0;
  for (double v : angular) mean += v;
  mean /= static_cast<double>(angular.size());
  const double width = 180.0 / static_cast<double>(angular.size());
  std::printf("angular        mean power over %.3g <= |v| <= %d: %.3g; darkest bins:", r_min, m,
              mean);
  for (size_t i = 0; i < std::min<size_t>(5, order.size()); ++i) {
    std::printf(" [%g, %g) %.3g%s", order[i] * width, (order[i] + 1) * width, angular[order[i]],
                i + 1 < std::min<size_t>(5, order.size()) ? "," : "");
  }
  std::printf("\n");
  if (!o.png.empty()) std::printf("wrote          %s\n", o.png.c_str());
  return kExitOk;
}

}  // namespace

void AddAnalyzeCommand(CLI::App& app) {
  auto o = std::make_shared<AnalyzeOptions>();
  CLI::App* c = AddCommand(app, "analyze",
                           "expected power spectrum of point sets: radial, directional and angular "
                           "profiles\n(several files or multi-set files: the mean over the sets)");
  c->add_option("SET", o->files,
                "point-set files (UTK text, .npy, .csv; - stdin), one or several sets each, one N")
      ->required();
  c->add_option("--dir", o->dirs,
                "direction (degrees) for a directional profile besides 0 and 90, repeatable")
      ->allow_extra_args(false)
      ->check(FiniteNumber());
  c->add_option("--max-freq", o->max_frequency,
                "largest |a|, |b| of the spectrum (default: 2 sqrt(N), in [8, 256])")
      ->check(IntegerIn(1, 1024));
  c->add_option("--bins", o->bins, "angle bins of the angular profile over [0, 180)")
      ->capture_default_str()
      ->check(IntegerIn(4, 3600));
  c->add_option("--r-min", o->r_min,
                "smallest |v| in the angular profile (default: max(4, max-freq / 8))")
      ->check(FiniteIn(0.0, 1e4));
  c->add_option("--png", o->png, "write a figure (spectrum, radial, directional, angular)");
  c->add_option("--title", o->title, "title of the figure");
  c->add_flag("--json", o->json, "print everything as JSON instead of the summary");
  c->add_option("--engine", o->engine, "spectral engine: auto, direct, fast or cuda")
      ->capture_default_str();
  c->add_option("--threads", o->threads, "engine threads (0: all cores)")
      ->capture_default_str()
      ->check(IntegerIn(0, 1024));
  OnRun(c, [o] { return RunAnalyze(*o); });
}

}  // namespace alignset::cli

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
#include "core/analysis/convergence.h"
#include "core/analysis/integrands.h"
#include "core/analysis/variance.h"
#include "core/sampling/samplers.h"
#include "core/spectral/spectral_engine.h"

namespace alignset::cli {
namespace {

struct ConvergenceOptions {
  std::vector<std::string> samplers;
  std::vector<std::string> set_specs;  // LABEL=PATTERN with {n}
  std::vector<std::string> integrands;
  std::vector<int64_t> n = {256, 1024, 4096};
  int64_t seeds = 8;
  uint64_t seed = 1;
  int64_t shifts = 1024;
  uint64_t shift_seed = 7;
  std::string homogenize = "cp";
  std::string method = "mc";
  int64_t radius = 0;
  std::string png;
  std::string title;
  bool json = false;
  std::string engine = "auto";
  int64_t threads = 0;
};

int Usage(const Status& s) { return ReportError("convergence", s, kExitUsage); }
int Failure(const Status& s) { return ReportError("convergence", s, kExitFailure); }

// Where the sets of one curve come from: a sampler (seeds seed .. seed + m - 1)
// or point files, one per N, named by a pattern with {n}.
struct Source {
  std::string label;
  std::string sampler;  // empty: pattern
  std::string pattern;
};

std::string Expand(const std::string& pattern, int64_t n) {
  std::string out = pattern;
  const std::string key = "{n}";
  for (size_t at = out.find(key); at != std::string::npos; at = out.find(key, at)) {
    out.replace(at, key.size(), std::to_string(n));
  }
  return out;
}

struct Series {
  std::string label, integrand, homogenize;
  std::vector<double> n, variance, std_error;
  int sets = 0;
  double slope = NAN;
};

std::string ToJson(const ConvergenceOptions& o, const std::vector<Series>& series) {
  std::string j = "{\"kind\":\"convergence\",\"title\":" + JsonString(o.title) +
                  ",\"method\":" + JsonString(o.method) + ",\"shifts\":" +
                  std::to_string(o.shifts) + ",\"series\":[";
  for (size_t i = 0; i < series.size(); ++i) {
    const Series& s = series[i];
    j += std::string(i ? "," : "") + "{\"label\":" + JsonString(s.label) +
         ",\"integrand\":" + JsonString(s.integrand) + ",\"homogenize\":" +
         JsonString(s.homogenize) + ",\"sets\":" + std::to_string(s.sets) +
         ",\"n\":" + JsonArray(s.n) + ",\"variance\":" + JsonArray(s.variance) +
         ",\"std_error\":" + JsonArray(s.std_error) + ",\"slope\":" + JsonNumber(s.slope) + "}";
  }
  return j + "]}\n";
}

int RunConvergence(const ConvergenceOptions& o) {
  if (o.samplers.empty() && o.set_specs.empty()) {
    return Usage(Status::InvalidArgument("name at least one --sampler or --set LABEL=PATTERN"));
  }
  if (o.homogenize != "cp" && o.homogenize != "none" && o.homogenize != "both") {
    return Usage(Status::InvalidArgument("--homogenize must be cp, none or both, got '" +
                                         o.homogenize + "'"));
  }
  if (o.method != "mc" && o.method != "exact") {
    return Usage(Status::InvalidArgument("--method must be mc or exact, got '" + o.method + "'"));
  }
  if (o.method == "exact" && o.homogenize != "cp") {
    return Usage(Status::InvalidArgument(
        "--method exact is the CP variance (Eq. 18): use it with --homogenize cp"));
  }
  std::vector<Source> sources;
  const std::vector<std::string> known = SamplerNames();
  for (const std::string& name : o.samplers) {
    if (std::find(known.begin(), known.end(), name) == known.end()) {
      auto probe = Sample(name, 256, 1);  // its message lists the known names
      return Usage(probe.status());
    }
    sources.push_back({name, name, ""});
  }
  for (const std::string& spec : o.set_specs) {
    const size_t eq = spec.find('=');
    if (eq == std::string::npos || eq == 0 || spec.find("{n}", eq) == std::string::npos) {
      return Usage(Status::InvalidArgument("--set '" + spec +
                                           "': expected LABEL=PATTERN, the pattern naming the "
                                           "file of each N with {n} (e.g. mine=sets/n{n}.npy)"));
    }
    sources.push_back({spec.substr(0, eq), "", spec.substr(eq + 1)});
  }
  std::vector<std::unique_ptr<Integrand>> integrands;
  for (const std::string& spec : o.integrands) {
    auto f = MakeIntegrand(spec);
    if (!f.ok()) return Usage(f.status());
    integrands.push_back(std::move(f).value());
  }
  auto kind = ParseEngineKind(o.engine);
  if (!kind.ok()) return Usage(kind.status());
  std::unique_ptr<SpectralEngine> engine;
  if (o.method == "exact") {
    auto made = MakeSpectralEngine(*kind, static_cast<int>(o.threads));
    if (!made.ok()) return Failure(made.status());
    engine = std::move(made).value();
  }
  std::vector<std::string> modes;
  if (o.homogenize == "cp" || o.homogenize == "both") modes.push_back("cp");
  if (o.homogenize == "none" || o.homogenize == "both") modes.push_back("none");

  // Read or make every set first: a bad file or N fails before the work.
  // sets[source][n]
  std::vector<std::vector<std::vector<PointSet>>> sets(sources.size());
  for (size_t s = 0; s < sources.size(); ++s) {
    for (int64_t n : o.n) {
      std::vector<PointSet> at_n;
      if (!sources[s].sampler.empty()) {
        for (int64_t i = 0; i < o.seeds; ++i) {
          auto p = Sample(sources[s].sampler, static_cast<uint32_t>(n), o.seed + i);
          if (!p.ok()) return Usage(p.status());
          at_n.push_back(std::move(p).value());
        }
      } else {
        const std::string path = Expand(sources[s].pattern, n);
        auto read = ReadPointSets(path);
        if (!read.ok()) return Usage(read.status());
        for (PointSet& p : *read) {
          if (p.size() != static_cast<size_t>(n)) {
            return Usage(Status::InvalidArgument(path + " holds a set of " +
                                                 std::to_string(p.size()) + " points, expected " +
                                                 std::to_string(n)));
          }
          at_n.push_back(std::move(p));
        }
      }
      sets[s].push_back(std::move(at_n));
    }
  }

  std::vector<Series> series;
  for (size_t s = 0; s < sources.size(); ++s) {
    for (const auto& f : integrands) {
      for (const std::string& mode : modes) {
        Series line;
        line.label = sources[s].label + (o.homogenize == "both" ? (mode == "cp" ? " (CP)" : " (no CP)") : "");
        line.integrand = f->name();
        line.homogenize = mode;
        for (size_t k = 0; k < o.n.size(); ++k) {
          const std::vector<PointSet>& at_n = sets[s][k];
          VarianceEstimate v;
          if (mode == "none") {
            v = PlainVarianceOverSets(at_n, *f);
          } else if (o.method == "exact") {
            const int radius = o.radius > 0
                                   ? static_cast<int>(o.radius)
                                   : std::min(1024, static_cast<int>(std::lround(
                                                        4.0 * std::sqrt(double(o.n[k])))));
            v = ExactCpVarianceOverSets(at_n, *f, radius, *engine);
          } else {
            v = CpVarianceOverSets(at_n, *f, static_cast<int>(o.shifts), o.shift_seed);
          }
          line.n.push_back(static_cast<double>(o.n[k]));
          line.variance.push_back(v.variance);
          line.std_error.push_back(v.std_error);
          line.sets = static_cast<int>(at_n.size());
        }
        if (line.n.size() >= 2) line.slope = LogLogSlope(line.n, line.variance);
        series.push_back(std::move(line));
      }
    }
  }

  const std::string json = ToJson(o, series);
  if (!o.png.empty()) {
    if (Status s = WritePlot(json, o.png); !s.ok()) return Failure(s);
  }
  if (o.json) {
    std::fputs(json.c_str(), stdout);
    return kExitOk;
  }
  std::printf("# variance of the %s estimator (%s), mean over the sets; slope: least squares of "
              "log variance on log N\n",
              o.homogenize == "none" ? "plain" : o.homogenize == "both" ? "CP-rotated and plain"
                                                                        : "CP-rotated",
              o.method == "exact" ? "Eq. 18" : "Monte Carlo");
  std::printf("# sampler\tintegrand\tsets");
  for (int64_t n : o.n) std::printf("\tN=%lld\t+-", static_cast<long long>(n));
  std::printf("\tslope\n");
  for (const Series& s : series) {
    std::printf("%s\t%s\t%d", s.label.c_str(), s.integrand.c_str(), s.sets);
    for (size_t k = 0; k < s.n.size(); ++k) {
      std::printf("\t%.4e\t%.2e", s.variance[k], s.std_error[k]);
    }
    std::printf("\t%.3f\n", s.slope);
  }
  if (!o.png.empty()) std::printf("# wrote %s\n", o.png.c_str());
  return kExitOk;
}

}  // namespace

void AddConvergenceCommand(CLI::App& app) {
  auto o = std::make_shared<ConvergenceOptions>();
  CLI::App* c = AddCommand(
      app, "convergence",
      "variance against N for samplers and point files on chosen integrands, with fitted slopes");
  c->add_option("--sampler", o->samplers, "a sampler by name ('alignset sample --list'), repeatable")
      ->allow_extra_args(false);
  c->add_option("--set", o->set_specs,
                "LABEL=PATTERN: point files, one per N ({n} in the name), each with one or\n"
                "several sets (e.g. aligned=sets/a_n{n}.npy from alignset optimize -m), repeatable")
      ->allow_extra_args(false);
  c->add_option("--integrand", o->integrands,
                "integrand spec, repeatable: step:DEG[:OFF] smoothstep:DEG[:W[:OFF]] disk[:R[:CX:CY]]\n"
                "triangle polygon:K[:ROT] edges:D1:D2:D3[:...] gaussian[:SIGMA] product boundary")
      ->required()
      ->allow_extra_args(false);
  c->add_option("-n,--n", o->n, "point counts, comma-separated")
      ->delimiter(',')
      ->capture_default_str()
      ->check(IntegerIn(1, 1 << 22));
  c->add_option("-m,--seeds", o->seeds, "sets per sampler and N (seeds S, S+1, ...)")
      ->capture_default_str()
      ->check(IntegerIn(1, 100000));
  c->add_option("-s,--seed", o->seed, "first sampler seed")->capture_default_str()->check(SeedValue());
  c->add_option("--shifts", o->shifts, "Cranley-Patterson shifts per set (Monte Carlo)")
      ->capture_default_str()
      ->check(IntegerIn(16, 1 << 24));
  c->add_option("--shift-seed", o->shift_seed, "seed of the shifts (the same for every set)")
      ->capture_default_str()
      ->check(SeedValue());
  c->add_option("--homogenize", o->homogenize,
                "cp: Cranley-Patterson rotated; none: the sets as they are (variance over the\n"
                "sampler's own randomization; needs many seeds); both")
      ->capture_default_str();
  c->add_option("--method", o->method,
                "mc: Monte Carlo over the shifts; exact: Eq. 18 with the Parseval tail")
      ->capture_default_str();
  c->add_option("--radius", o->radius, "frequency radius of --method exact (default 4 sqrt(N))")
      ->check(IntegerIn(1, 4096));
  c->add_option("--png", o->png, "write the log-log plot");
  c->add_option("--title", o->title, "title of the plot");
  c->add_flag("--json", o->json, "print the series as JSON instead of the table");
  c->add_option("--engine", o->engine, "spectral engine of --method exact")->capture_default_str();
  c->add_option("--threads", o->threads, "engine threads (0: all cores)")
      ->capture_default_str()
      ->check(IntegerIn(0, 1024));
  OnRun(c, [o] { return RunConvergence(*o); });
}

}  // namespace alignset::cli

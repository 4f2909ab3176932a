// `alignset joint`: the joint lattice a renderer's pixel gets
// (<alignset/joint_lattice.h>), to look at before rendering with it: its
// generator, how many of the dimensions asked for the lattice keeps at this
// N, every 2-D projection's spacing and the search's time; with --out, one
// pixel's N points in every dimension asked (the padding's too), as the
// renderer reads them; with --png, a figure of their 2-D projections. The
// sampler library searches the generator at Create
// in milliseconds (seconds at N = 65536), so no table holds it: this command
// is where a user sees what that search chose.
#include <alignset/joint_lattice.h>
#include <alignset/npy.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "cli/commands.h"
#include "cli/json_text.h"
#include "cli/plot_script.h"
#include "cli/point_file.h"
#include "client/whole_file.h"

namespace alignset::cli {
namespace {

struct JointOptions {
  int64_t n = 0;
  int64_t dimensions = 0;
  uint64_t seed = 1;
  uint64_t pixel = 0;
  std::vector<std::string> folds;  // "D:H"
  std::vector<int64_t> tents;
  bool jitter = false;
  int64_t padded = 0;
  std::string out;
  std::string png;
};

// The dimensions --png draws (every pair of them): more would be panels too
// small to read.
constexpr uint32_t kPlottedDimensions = 5;

int Usage(const Status& s) { return ReportError("joint", s, kExitUsage); }

// "D:H" -> folds[D] = H (the library checks H and that D is a dimension).
Status ParseFolds(const std::vector<std::string>& specs, uint32_t dimensions,
                  std::vector<uint32_t>* folds) {
  folds->assign(dimensions, 1);
  for (const std::string& spec : specs) {
    unsigned d = 0, h = 0;
    char end = 0;
    if (std::sscanf(spec.c_str(), "%u:%u%c", &d, &h, &end) != 2) {
      return Status::InvalidArgument("--fold " + spec + ": expected D:H (dimension D has period 1/H)");
    }
    if (d >= dimensions) {
      return Status::InvalidArgument("--fold " + spec + ": dimension " + std::to_string(d) +
                                     " is not below --dimensions " + std::to_string(dimensions));
    }
    (*folds)[d] = h;
  }
  return Status::Ok();
}

// The pixel's values, row i = sample i, column d = dimension d.
Status WriteValues(const std::string& path, uint32_t n, uint32_t columns, const std::vector<double>& v,
                   const std::string& comment) {
  const FileFormat format = FileFormatOf(path);
  if (format == FileFormat::kNpy) return WriteNpy(path, {n, columns}, v);
  const bool csv = format == FileFormat::kCsv;
  std::string text = csv ? "" : "# " + comment + "\n";
  for (uint32_t d = 0; csv && d < columns; ++d) text += (d ? ",d" : "d") + std::to_string(d);
  if (csv) text += "\n";
  char cell[40];
  for (uint32_t i = 0; i < n; ++i) {
    for (uint32_t d = 0; d < columns; ++d) {
      std::snprintf(cell, sizeof(cell), "%s%.17g", d ? (csv ? "," : " ") : "", v[size_t(i) * columns + d]);
      text += cell;
    }
    text += "\n";
  }
  if (IsStdStream(path)) {
    std::fputs(text.c_str(), stdout);
    return Status::Ok();
  }
  return WriteWholeFile(path, text);
}

// scripts/plot_analysis.py's "joint" document: the pixel's values in the
// first lattice dimensions (columns; a folded one as its lattice coordinate
// frac(h u), what the integrand sees and the spacing is of) and each pair's
// spacing.
std::string PlotJson(const JointLattice& lattice, const std::vector<uint32_t>& folds,
                     const std::vector<double>& values, uint32_t columns, const std::string& title) {
  const uint32_t k = std::min(lattice.dimensions(), kPlottedDimensions);
  const std::vector<uint32_t>& z = lattice.generator();
  std::string json = "{\"kind\": \"joint\", \"title\": " + JsonString(title) + ", \"labels\": [";
  for (uint32_t d = 0; d < k; ++d) {
    const std::string label = "d" + std::to_string(d);
    json += (d ? ", " : "") +
            JsonString(folds[d] > 1 ? label + " as frac(" + std::to_string(folds[d]) + " u)" : label);
  }
  json += "], \"columns\": [";
  for (uint32_t d = 0; d < k; ++d) {
    std::vector<double> column(lattice.n());
    for (uint32_t i = 0; i < lattice.n(); ++i) {
      const double u = values[size_t(i) * columns + d] * folds[d];
      column[i] = u - std::floor(u);
    }
    json += (d ? ", " : "") + JsonArray(column);
  }
  json += "], \"spacing\": [";
  for (uint32_t b = 1; b < k; ++b) {
    for (uint32_t a = 0; a < b; ++a) {
      json += (a + b > 1 ? ", [" : "[") + std::to_string(a) + ", " + std::to_string(b) + ", " +
              JsonNumber(JointLatticePairSpacing(lattice.n(), z[a], z[b])) + "]";
    }
  }
  return json + "]}";
}

int RunJoint(const JointOptions& o) {
  if (o.n == 0) return Usage(Status::InvalidArgument("--n is required"));
  if (o.dimensions == 0) return Usage(Status::InvalidArgument("--dimensions is required"));
  const auto n = static_cast<uint32_t>(o.n);
  const auto dims = static_cast<uint32_t>(o.dimensions);
  std::vector<uint32_t> folds;
  if (Status s = ParseFolds(o.folds, dims, &folds); !s.ok()) return Usage(s);
  std::vector<bool> tents(dims, false);
  for (int64_t d : o.tents) {
    if (d >= o.dimensions) {
      return Usage(Status::InvalidArgument("--tent " + std::to_string(d) + ": not below --dimensions " +
                                           std::to_string(dims)));
    }
    tents[size_t(d)] = true;
  }
  const auto t0 = std::chrono::steady_clock::now();
  StatusOr<JointLattice> made = JointLattice::Create(n, dims, o.seed, folds, tents, o.jitter);
  const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  if (!made.ok()) return Usage(made.status());
  const JointLattice& lattice = *made;
  if (!o.png.empty() && lattice.dimensions() < 2) {
    return Usage(Status::InvalidArgument("--png: at N = " + std::to_string(n) +
                                         " the lattice keeps one dimension, no pair to draw"));
  }
  const std::vector<uint32_t>& z = lattice.generator();
  FILE* report = ReportStreamFor(o.out);

  std::fprintf(report, "joint lattice: N = %u, %u of the %u dimensions asked in the lattice%s (searched in %.1f ms)\n",
               n, lattice.dimensions(), dims,
               lattice.dimensions() < dims ? ", the rest padded with scrambled Sobol points" : "", ms);
  std::fprintf(report, "generator:");
  for (uint32_t zj : z) std::fprintf(report, " %u", zj);
  std::fprintf(report, "\nweighted P_2 (smaller is better): %.6g\n", JointLatticeP2(n, z));
  std::fprintf(report,
               "2-D projections: the shortest dual vector squared over the Hermite bound "
               "(1: hexagonal; near 0: on a few lines)\n     ");
  for (uint32_t a = 0; a + 1 < z.size(); ++a) std::fprintf(report, "  d%-4u", a);
  std::fprintf(report, "\n");
  for (uint32_t b = 1; b < z.size(); ++b) {
    std::fprintf(report, "d%-4u", b);
    for (uint32_t a = 0; a < b; ++a) std::fprintf(report, "  %.3f", JointLatticePairSpacing(n, z[a], z[b]));
    std::fprintf(report, "\n");
  }
  for (uint32_t d = 0; d < dims; ++d) {
    if (folds[d] > 1) std::fprintf(report, "d%u folded: period 1/%u, the lattice coordinate is frac(%u u)\n", d, folds[d], folds[d]);
    if (lattice.tented(d)) std::fprintf(report, "d%u tented\n", d);
  }
  if (o.out.empty() && o.png.empty()) return kExitOk;

  const uint32_t columns = dims + static_cast<uint32_t>(o.padded);
  std::vector<double> values(size_t(n) * columns);
  for (uint32_t i = 0; i < n; ++i) {
    for (uint32_t d = 0; d < columns; ++d) values[size_t(i) * columns + d] = lattice.Sample(o.pixel, i, d);
  }
  const std::string comment = "alignset joint N=" + std::to_string(n) + " dimensions=" + std::to_string(dims) +
                              " seed=" + std::to_string(o.seed) + " pixel=" + std::to_string(o.pixel) +
                              (o.jitter ? " jittered" : " shifted") +
                              (o.padded ? " padded=" + std::to_string(o.padded) : "");
  if (!o.out.empty()) {
    if (Status s = WriteValues(o.out, n, columns, values, comment); !s.ok()) {
      return ReportError("joint", s, kExitFailure);
    }
    std::fprintf(report, "wrote pixel %llu's %u points in %u dimensions to %s\n",
                 static_cast<unsigned long long>(o.pixel), n, columns, o.out.c_str());
  }
  if (!o.png.empty()) {
    if (Status s = WritePlot(PlotJson(lattice, folds, values, columns, comment), o.png); !s.ok()) {
      return ReportError("joint", s, kExitFailure);
    }
    std::fprintf(report, "wrote the 2-D projections of the first %u dimensions to %s\n",
                 std::min(lattice.dimensions(), kPlottedDimensions), o.png.c_str());
  }
  return kExitOk;
}

}  // namespace

void AddJointCommand(CLI::App& app) {
  auto o = std::make_shared<JointOptions>();
  CLI::App* c = AddCommand(app, "joint",
                           "the joint lattice a renderer's pixel gets (the sampler library's JointLattice, pbrt's\n"
                           "align \"joint\"): its generator, the dimensions it keeps, every 2-D projection's\n"
                           "spacing; --out: one pixel's points in every dimension (.npy (N, D), .csv, text; - stdout);\n"
                           "--png: their 2-D projections");
  c->add_option("-n,--n", o->n, "points a pixel (the renderer's samples a pixel)")->check(IntegerIn(2, 65536));
  c->add_option("-d,--dimensions", o->dimensions, "the dimensions asked for the lattice")
      ->check(IntegerIn(1, kJointLatticeMaxDimensions));
  c->add_option("-s,--seed", o->seed, "seed")->capture_default_str()->check(SeedValue());
  c->add_option("--pixel", o->pixel, "the pixel's index (the renderer's, e.g. y * width + x)")
      ->capture_default_str();
  c->add_option("--fold", o->folds,
                "D:H, dimension D has period 1/H (pbrt's wavelength: H = 4); repeatable");
  c->add_option("--tent", o->tents, "dimension D tented after its shift; repeatable")
      ->check(IntegerIn(0, kJointLatticeMaxDimensions - 1));
  c->add_flag("--jitter", o->jitter, "each point anywhere in its stratum instead of shifted");
  c->add_option("--padded", o->padded, "with --out, this many padded dimensions more")
      ->check(IntegerIn(0, 64));
  c->add_option("-o,--out", o->out, "the pixel's points: .npy (N, D), .csv, text; - stdout");
  c->add_option("--png", o->png, "a figure of the pixel's points: every 2-D projection of the first five "
                                 "lattice dimensions, each with its spacing");
  OnRun(c, [o] { return RunJoint(*o); });
}

}  // namespace alignset::cli

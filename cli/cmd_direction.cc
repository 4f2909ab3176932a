#include <cmath>
#include <cstdio>
#include <memory>
#include <string>

#include "cli/commands.h"
#include "cli/patch_file.h"
#include "core/analysis/direction_estimate.h"

namespace alignset::cli {
namespace {

int Usage(const Status& s) { return ReportError("direction", s, kExitUsage); }

struct DirectionCommandOptions {
  std::string file;
  bool two = false;
  bool json = false;
};

std::string JsonString(const std::string& s) {
  std::string out = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\') out += '\\';
    if (static_cast<unsigned char>(c) < 0x20) continue;  // reasons are one line
    out += c;
  }
  return out + "\"";
}

std::string Number(const char* format, double v) {
  char buf[64];
  std::snprintf(buf, sizeof(buf), format, v);
  return buf;
}

// Degrees to four places: the estimate is finer than the service's
// quarter-degree grid, and it is printed as estimated, not rounded to it.
std::string Degrees(double v) { return Number("%.4f", v); }

void PrintText(const DirectionEstimate& e, bool two) {
  const DirectionLobe& d = e.first;
  if (d.status != DirectionStatus::kFound) {
    std::printf("theta none\nreason %s\n", d.reason.c_str());
    return;
  }
  std::printf("theta %s\nkappa %s\nconfidence %s\n", Degrees(d.theta_deg).c_str(),
              Number("%.6g", d.kappa).c_str(), Number("%.4f", d.confidence).c_str());
  if (two) {
    std::printf("theta2 %s\n", e.has_second && e.second.status == DirectionStatus::kFound
                                   ? Degrees(e.second.theta_deg).c_str()
                                   : "none");
  }
}

void PrintJson(const DirectionEstimate& e, bool two) {
  const DirectionLobe& d = e.first;
  std::string s = "{";
  if (d.status == DirectionStatus::kFound) {
    s += "\"theta\": " + Degrees(d.theta_deg) + ", \"kappa\": " + Number("%.6g", d.kappa) +
         ", \"confidence\": " + Number("%.4f", d.confidence);
    if (two) {
      const bool found2 = e.has_second && e.second.status == DirectionStatus::kFound;
      s += ", \"theta2\": " + (found2 ? Degrees(e.second.theta_deg) : std::string("null"));
    }
  } else {
    s += "\"theta\": null, \"reason\": " + JsonString(d.reason);
  }
  std::printf("%s}\n", s.c_str());
}

int RunDirection(const DirectionCommandOptions& o) {
  auto input = ReadPatchFile(o.file);
  if (!input.ok()) return Usage(input.status());
  DirectionOptions options;
  options.second = o.two;
  auto estimate = input->is_grid ? EstimateDirection(input->grid, options)
                                 : EstimateDirection(input->samples, options);
  if (!estimate.ok()) return Usage(estimate.status());
  if (o.json) {
    PrintJson(*estimate, o.two);
  } else {
    PrintText(*estimate, o.two);
  }
  return estimate->first.status == DirectionStatus::kFound ? kExitOk : kExitFailure;
}

}  // namespace

void AddDirectionCommand(CLI::App& app) {
  auto o = std::make_shared<DirectionCommandOptions>();
  CLI::App* c = AddCommand(
      app, "direction",
      "the principal direction of an integrand (von Mises fit to its power spectrum):\n"
      "the edge normal to ask `alignset get --dir` for");
  c->add_option("FILE", o->file,
                ".npy grid of values, shape (H, W): values[j, i] = f((i+1/2)/W, (j+1/2)/H),\n"
                "rows along y; or text: one 'x y f' sample per line ('#' comments; - stdin)")
      ->required();
  c->add_flag("--two", o->two, "also the second direction (for 4-direction sets): theta2");
  c->add_flag("--json", o->json, "the same fields as one JSON object");
  c->footer(
      "Prints 'theta <deg>' (spectral convention, [0, 180)), 'kappa <value>' and\n"
      "'confidence <share of the spectral energy in the fitted lobe>', one per line,\n"
      "and 'theta2 <deg>' (or 'theta2 none') with --two. An integrand without a\n"
      "dominant direction (constant, noise, a disk) prints 'theta none' and 'reason ...'\n"
      "and exits with status 1.\n\n" +
      std::string(kExitStatusHelp));
  OnRun(c, [o] { return RunDirection(*o); });
}

}  // namespace alignset::cli

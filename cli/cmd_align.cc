#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "cli/commands.h"
#include "cli/point_file.h"
#include "core/align/canonical.h"

namespace alignset::cli {
namespace {

struct AlignOptions {
  std::string in;
  std::vector<double> canonical;
  std::vector<double> dirs;
  std::string out;
};

int Usage(const Status& s) { return ReportError("align", s, kExitUsage); }

// Aligns a set optimized for a canonical key onto the requested directions
// (degrees, spectral direction = edge normal). The request's key must be the
// set's key, so a set is never silently aligned from the wrong orbit.
int RunAlign(const AlignOptions& o) {
  if (o.canonical.size() != o.dirs.size()) {
    return Usage(Status::InvalidArgument("give as many --canonical as --dir angles"));
  }
  auto request = Canonicalize(o.dirs);
  if (!request.ok()) return Usage(request.status());
  auto key = Canonicalize(o.canonical);
  if (!key.ok()) return Usage(key.status());
  if (!(key->key == request->key) || !(key->ops == AlignOps{})) {
    return Usage(Status::InvalidArgument("the request needs the set of key " +
                                         ToString(request->key) + "; --canonical names " +
                                         (key->ops == AlignOps{} ? ToString(key->key)
                                                                 : "a non-canonical direction")));
  }
  // Every set of a multi-set file is aligned, and written as several again.
  auto sets = ReadPointSets(o.in);
  if (!sets.ok()) return Usage(sets.status());
  std::vector<PointSet> aligned;
  for (const PointSet& s : *sets) aligned.push_back(Align(s, request->ops));
  std::string served;
  for (int d : request->served_deg) served += (served.empty() ? "" : ",") + std::to_string(d);
  const std::string comment = "alignset align: key " + ToString(request->key) + " -> " + served +
                              " deg (spectral direction = edge normal) by " +
                              ToString(request->ops);
  const Status written = aligned.size() > 1 ? WritePointSets(o.out, aligned, comment)
                                            : WritePointFile(o.out, aligned[0], comment);
  if (!written.ok()) return ReportError("align", written, kExitFailure);
  const std::string sets_text = aligned.size() > 1 ? std::to_string(aligned.size()) + " sets of " : "";
  std::fprintf(ReportStreamFor(o.out), "aligned %s%s to %s deg by %s: %s\n", sets_text.c_str(),
               ToString(request->key).c_str(), served.c_str(),
               ToString(request->ops).c_str(), o.out.c_str());
  return kExitOk;
}

}  // namespace

void AddAlignCommand(CLI::App& app) {
  auto o = std::make_shared<AlignOptions>();
  CLI::App* c = AddCommand(app, "align",
                           "align a canonical set onto requested directions (swap / invert)");
  c->add_option("FILE", o->in, "the canonical set(s): UTK text, .npy, .csv; - stdin")->required();
  c->add_option("--canonical", o->canonical,
                "the set's canonical direction(s), degrees (one per --dir)")
      ->required()
      ->allow_extra_args(false)
      ->check(FiniteNumber());
  c->add_option("--dir", o->dirs, "requested direction(s), degrees (edge normal), one or two")
      ->required()
      ->allow_extra_args(false)
      ->check(FiniteNumber());
  c->add_option("-o,--out", o->out, "output file: UTK text, .npy, .csv by extension; - stdout")->required();
  OnRun(c, [o] { return RunAlign(*o); });
}

}  // namespace alignset::cli

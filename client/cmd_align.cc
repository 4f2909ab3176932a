#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "client/commands.h"
#include "client/point_file.h"
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
  auto points = ReadPointFile(o.in);
  if (!points.ok()) return Usage(points.status());
  const PointSet aligned = Align(*points, request->ops);
  std::string served;
  for (int d : request->served_deg) served += (served.empty() ? "" : ",") + std::to_string(d);
  const std::string comment = "alignset align: key " + ToString(request->key) + " -> " + served +
                              " deg (spectral direction = edge normal) by " +
                              ToString(request->ops);
  if (Status s = WritePointFile(o.out, aligned, comment); !s.ok()) {
    return ReportError("align", s, kExitFailure);
  }
  std::printf("aligned %s to %s deg by %s: %s\n", ToString(request->key).c_str(), served.c_str(),
              ToString(request->ops).c_str(), o.out.c_str());
  return kExitOk;
}

}  // namespace

void AddAlignCommand(CLI::App& app) {
  auto o = std::make_shared<AlignOptions>();
  CLI::App* c = AddCommand(app, "align",
                           "align a canonical set onto requested directions (swap / invert)");
  c->add_option("FILE", o->in, "the canonical set (UTK text or .npy)")->required();
  c->add_option("--canonical", o->canonical,
                "the set's canonical direction(s), degrees (one per --dir)")
      ->required()
      ->allow_extra_args(false)
      ->check(FiniteNumber());
  c->add_option("--dir", o->dirs, "requested direction(s), degrees (edge normal), one or two")
      ->required()
      ->allow_extra_args(false)
      ->check(FiniteNumber());
  c->add_option("-o,--out", o->out, "output file (UTK text, or .npy by extension)")->required();
  c->callback([o] { Finish(RunAlign(*o)); });
}

}  // namespace alignset::cli

#include <cstdio>
#include <string>
#include <vector>

#include "client/args.h"
#include "client/commands.h"
#include "client/point_file.h"
#include "core/align/canonical.h"

namespace alignset::cli {
namespace {

int Fail(const Status& s) { return ReportError("align", s, kExitUsage); }

}  // namespace

// alignset align IN --canonical PHI [--canonical PHI2] --dir DEG [--dir DEG2] --out OUT
// Aligns a set optimized for a canonical key onto the requested directions
// (degrees, spectral direction = edge normal). The request's key must be the
// set's key, so a set is never silently aligned from the wrong orbit.
int RunAlign(int argc, char** argv) {
  auto args = Args::Parse(argc, argv, {"canonical", "dir", "out"});
  if (!args.ok()) return Fail(args.status());
  if (args->positionals().size() != 1) {
    return Fail(Status::InvalidArgument("expected exactly one input point-set file"));
  }
  if (!args->Has("out")) return Fail(Status::InvalidArgument("--out is required"));
  auto canonical = args->Doubles("canonical");
  if (!canonical.ok()) return Fail(canonical.status());
  auto dirs = args->Doubles("dir");
  if (!dirs.ok()) return Fail(dirs.status());
  auto out = args->String("out", "");
  if (!out.ok()) return Fail(out.status());
  if (canonical->size() != dirs->size()) {
    return Fail(Status::InvalidArgument("give as many --canonical as --dir angles"));
  }
  auto request = Canonicalize(*dirs);
  if (!request.ok()) return Fail(request.status());
  auto key = Canonicalize(*canonical);
  if (!key.ok()) return Fail(key.status());
  if (!(key->key == request->key) || !(key->ops == AlignOps{})) {
    return Fail(Status::InvalidArgument("the request needs the set of key " +
                                        ToString(request->key) + "; --canonical names " +
                                        (key->ops == AlignOps{} ? ToString(key->key)
                                                                : "a non-canonical direction")));
  }
  auto points = ReadPointFile(args->positionals()[0]);
  if (!points.ok()) return Fail(points.status());
  const PointSet aligned = Align(*points, request->ops);
  std::string served;
  for (int d : request->served_deg) served += (served.empty() ? "" : ",") + std::to_string(d);
  const std::string comment = "alignset align: key " + ToString(request->key) + " -> " + served +
                              " deg (spectral direction = edge normal) by " +
                              ToString(request->ops);
  if (Status s = WritePointFile(*out, aligned, comment); !s.ok()) return Fail(s);
  std::printf("aligned %s to %s deg by %s: %s\n", ToString(request->key).c_str(), served.c_str(),
              ToString(request->ops).c_str(), out->c_str());
  return 0;
}

}  // namespace alignset::cli

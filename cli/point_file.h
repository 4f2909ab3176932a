#pragma once

#include <cstdio>
#include <string>
#include <vector>

#include "core/util/point_set.h"
#include "core/util/status.h"

namespace alignset::cli {

// Point-set files, by extension:
//   .npy  NumPy, little-endian float64 (float32 is read too), C or Fortran
//         order. Shape (N, 2) is one set, (m, N, 2) is m sets of N points. A
//         transposed (2, N) array with N != 2 is read as N points (the layout
//         is unambiguous); a flat array is an error that says how to reshape.
//   .csv  comma-separated "x,y" rows under an optional header line "x,y";
//         several sets as "set,x,y" rows (set = 0, 1, ...).
//   else  UTK's text format: one "x y" line per point; a line starting with
//         '#' ends the current set, so several sets are '#'-separated (comment
//         lines before the first point, or in a row, separate nothing).
//   -     standard input / output, in UTK's text format.
//
// Every coordinate read must lie in [0, 1): a point outside the unit torus is
// an error that names the file, the set and the point.
//
// Writes go to a temporary file beside the target, then rename(2): a reader
// (or a crash) never sees half a file.

// True for the path that means standard output / input.
bool IsStdStream(const std::string& path);
// A file's format by its path, as above: .npy, .csv, anything else (and "-")
// text. Every command that reads or writes such files decides by this.
enum class FileFormat { kText, kNpy, kCsv };
FileFormat FileFormatOf(const std::string& path);
// Where a command reports what it did: stdout, unless its points go there.
FILE* ReportStreamFor(const std::string& out_path);

// Several sets: text with '#' separators, .npy of shape (m, N, 2) (all sets
// must have the same N), CSV "set,x,y". `comment` goes first in text files.
Status WritePointSets(const std::string& path, const std::vector<PointSet>& sets,
                      const std::string& comment = "");
// One set: .npy of shape (N, 2), CSV "x,y".
Status WritePointFile(const std::string& path, const PointSet& points,
                      const std::string& comment = "");

// Every set in the file (at least one, none empty).
StatusOr<std::vector<PointSet>> ReadPointSets(const std::string& path);
// The same from a file's bytes, its format told by `path`'s extension (.npy,
// .csv, anything else text; "-" text): what ReadPointSets parses, and what
// the fuzzer feeds (fuzz/point_file_fuzzer.cc).
StatusOr<std::vector<PointSet>> ParsePointSets(const std::string& data, const std::string& path);
// Exactly one set; a file holding several is an error (for commands that
// read one set).
StatusOr<PointSet> ReadPointFile(const std::string& path);

}  // namespace alignset::cli

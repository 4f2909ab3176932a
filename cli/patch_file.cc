#include "cli/patch_file.h"

#include <algorithm>
#include <cerrno>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iostream>
#include <iterator>
#include <sstream>

#include <alignset/npy.h>
#include "cli/point_file.h"

namespace alignset::cli {
namespace {

// The core validators' messages, prefixed with the file's name.
Status InFile(const std::string& path, const Status& s) {
  return s.ok() ? s : Status::InvalidArgument(path + ": " + s.message());
}

StatusOr<PatchInput> ParseGrid(const std::string& data, const std::string& path) {
  auto array = ParseNpyArray(data, path, [&](const std::vector<size_t>& shape) {
    if (shape.size() != 2) {
      return Status::InvalidArgument(path + ": shape " + NpyShapeText(shape) +
                                     " is not a grid (H, W) of values");
    }
    return InFile(path, ValidateGridSize(static_cast<int64_t>(std::min<size_t>(shape[1], INT64_MAX)),
                                         static_cast<int64_t>(std::min<size_t>(shape[0], INT64_MAX))));
  });
  if (!array.ok()) return array.status();
  PatchInput in;
  in.is_grid = true;
  in.grid.height = static_cast<int>(std::min<size_t>(array->shape[0], INT32_MAX));
  in.grid.width = static_cast<int>(std::min<size_t>(array->shape[1], INT32_MAX));
  in.grid.values = std::move(array->values);
  if (Status s = ValidateGridPatch(in.grid); !s.ok()) return InFile(path, s);
  return in;
}

StatusOr<PatchInput> ParseSamples(const std::string& data, const std::string& path) {
  PatchInput in;
  std::istringstream lines(data);
  size_t line_no = 0;
  for (std::string line; std::getline(lines, line);) {
    ++line_no;
    const size_t first = line.find_first_not_of(" \t\r");
    if (first == std::string::npos || line[first] == '#') continue;
    // strtod rather than >>, so that "nan" and "inf" parse and are then
    // refused as not finite, in the same words as the RPC's.
    std::istringstream fields(line);
    double v[3];
    int count = 0;
    bool numbers = true;
    for (std::string word; fields >> word; ++count) {
      char* end = nullptr;
      const double x = std::strtod(word.c_str(), &end);
      if (end != word.c_str() + word.size()) numbers = false;
      if (count < 3) v[count] = x;
    }
    if (!numbers || count != 3) {
      return Status::InvalidArgument(path + ":" + std::to_string(line_no) +
                                     ": expected three numbers \"x y f\"");
    }
    const double x = v[0], y = v[1], f = v[2];
    if (static_cast<int64_t>(in.samples.values.size()) >= kMaxPatchSamples) {
      return Status::InvalidArgument(path + ": more than " + std::to_string(kMaxPatchSamples) +
                                     " samples");
    }
    in.samples.points.push_back({x, y});
    in.samples.values.push_back(f);
  }
  if (in.samples.values.empty()) return Status::InvalidArgument(path + ": no samples");
  if (Status s = ValidateSampledPatch(in.samples); !s.ok()) return InFile(path, s);
  return in;
}

}  // namespace

StatusOr<PatchInput> ReadPatchFile(const std::string& path) {
  std::string data;
  if (IsStdStream(path)) {
    data.assign(std::istreambuf_iterator<char>(std::cin), std::istreambuf_iterator<char>());
  } else {
    std::ifstream in(path, std::ios::binary);
    if (!in) return Status::InvalidArgument("cannot read " + path + ": " + std::strerror(errno));
    data.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  if (FileFormatOf(path) == FileFormat::kNpy) return ParseGrid(data, path);
  return ParseSamples(data, path);
}

}  // namespace alignset::cli

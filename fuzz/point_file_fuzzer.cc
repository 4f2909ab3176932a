// A point file on any bytes, its format chosen by the first byte (text, CSV
// or .npy, as the extension chooses it): a status or sets of points in
// [0, 1)^2, none empty.
#include <cstdint>
#include <cstdlib>
#include <string>

#include "cli/point_file.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size < 1) return 0;
  static const char* const kNames[] = {"fuzz.txt", "fuzz.csv", "fuzz.npy"};
  const std::string bytes(reinterpret_cast<const char*>(data) + 1, size - 1);
  auto sets = alignset::cli::ParsePointSets(bytes, kNames[data[0] % 3]);
  if (!sets.ok()) return 0;
  if (sets->empty()) std::abort();
  for (const alignset::PointSet& s : *sets) {
    if (s.empty()) std::abort();
    for (const alignset::Point2& p : s) {
      if (!(p.x >= 0.0 && p.x < 1.0 && p.y >= 0.0 && p.y < 1.0)) std::abort();
    }
  }
  return 0;
}

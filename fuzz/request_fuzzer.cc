// Every RPC's key, as the server validates it: N, max N, one to nine
// directions (any doubles: NaN, infinities, huge) and the grid's
// steps_per_degree from the bytes. A status, or a key whose N is within
// [16, max N] and whose canonical directions are finite.
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <vector>

#include "server/validation.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size < 12) return 0;
  uint32_t n = 0, max_n = 0, steps = 0;
  std::memcpy(&n, data, 4);
  std::memcpy(&max_n, data + 4, 4);
  std::memcpy(&steps, data + 8, 4);
  std::vector<double> dirs;
  for (size_t at = 12; at + 8 <= size && dirs.size() < 9; at += 8) {
    double d = 0.0;
    std::memcpy(&d, data + at, 8);
    dirs.push_back(d);
  }
  auto grid = alignset::server::ResolveAngleGrid(steps, alignset::AngleGrid::kWholeDegree);
  auto key = grid.ok() ? alignset::server::ValidateAlignedSetRequest(n, dirs, max_n, *grid)
                       : alignset::server::ValidateAlignedSetRequest(n, dirs, max_n);
  if (key.ok() && (n < 16 || n > max_n)) std::abort();
  return 0;
}

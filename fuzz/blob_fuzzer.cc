// A cache row's blob on any bytes: the first four are the row's N, the next
// four its stored CRC, the rest the blob. UnpackPoints and VerifyAndUnpack
// give a status or points in [0, 1)^2 that pack back to the same bytes.
#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <span>

#include "storage/blob_codec.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size < 8) return 0;
  uint32_t n = 0, crc = 0;
  std::memcpy(&n, data, 4);
  std::memcpy(&crc, data + 4, 4);
  n %= 1u << 21;  // the blob's size decides anyway; keeps the expected size sane
  const std::span<const uint8_t> blob(data + 8, size - 8);
  auto points = alignset::storage::UnpackPoints(blob, n);
  if (points.ok()) {
    for (const alignset::Point2& p : *points) {
      if (!(p.x >= 0.0 && p.x < 1.0 && p.y >= 0.0 && p.y < 1.0)) std::abort();
    }
    const auto again = alignset::storage::PackPoints(*points);
    if (again.size() != blob.size() || !std::equal(again.begin(), again.end(), blob.begin())) std::abort();
  }
  (void)alignset::storage::VerifyAndUnpack(blob, crc, n);
  return 0;
}

#include "storage/blob_codec.h"

#include <bit>
#include <cmath>
#include <cstdio>
#include <string>

namespace alignset::storage {
namespace {

void PutLe64(uint64_t v, uint8_t* out) {
  for (int i = 0; i < 8; ++i) out[i] = static_cast<uint8_t>(v >> (8 * i));
}

uint64_t GetLe64(const uint8_t* in) {
  uint64_t v = 0;
  for (int i = 0; i < 8; ++i) v |= static_cast<uint64_t>(in[i]) << (8 * i);
  return v;
}

bool InUnitInterval(double v) { return std::isfinite(v) && v >= 0.0 && v < 1.0; }

}  // namespace

std::vector<uint8_t> PackPoints(const PointSet& points) {
  std::vector<uint8_t> out(points.size() * kBytesPerPoint);
  uint8_t* p = out.data();
  for (const Point2& q : points) {
    PutLe64(std::bit_cast<uint64_t>(q.x), p);
    PutLe64(std::bit_cast<uint64_t>(q.y), p + 8);
    p += kBytesPerPoint;
  }
  return out;
}

StatusOr<PointSet> UnpackPoints(std::span<const uint8_t> blob, uint32_t expected_n) {
  if (blob.size() != static_cast<size_t>(expected_n) * kBytesPerPoint) {
    return Status::DataLoss("point blob holds " + std::to_string(blob.size()) + " bytes, expected " +
                            std::to_string(static_cast<size_t>(expected_n) * kBytesPerPoint));
  }
  PointSet points(expected_n);
  const uint8_t* p = blob.data();
  for (uint32_t i = 0; i < expected_n; ++i, p += kBytesPerPoint) {
    points[i].x = std::bit_cast<double>(GetLe64(p));
    points[i].y = std::bit_cast<double>(GetLe64(p + 8));
    if (!InUnitInterval(points[i].x) || !InUnitInterval(points[i].y)) {
      return Status::DataLoss("point " + std::to_string(i) + " of the blob is outside [0,1)^2");
    }
  }
  return points;
}

StatusOr<PointSet> VerifyAndUnpack(std::span<const uint8_t> blob, uint32_t stored_crc,
                                   uint32_t expected_n) {
  const uint32_t actual = Crc32c(blob);
  if (actual != stored_crc) {
    char msg[96];
    std::snprintf(msg, sizeof(msg), "checksum mismatch: stored crc32c %08x, blob has %08x",
                  stored_crc, actual);
    return Status::DataLoss(msg);
  }
  return UnpackPoints(blob, expected_n);
}

}  // namespace alignset::storage

#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "core/util/crc32c.h"
#include "core/util/point_set.h"
#include "core/util/status.h"

namespace alignset::storage {

// The blob checksum (core/util/crc32c.h).
using ::alignset::Crc32c;

// Bytes per point in a blob: x then y, each an IEEE-754 binary64.
inline constexpr size_t kBytesPerPoint = 16;

// x0 y0 x1 y1 ... as little-endian float64, whatever the host's byte order.
std::vector<uint8_t> PackPoints(const PointSet& points);

// The inverse of PackPoints. DataLoss when the size is not 16 * expected_n
// or a coordinate is not a finite number in [0, 1): a stored set is always
// inside the unit square, so anything else is damage.
StatusOr<PointSet> UnpackPoints(std::span<const uint8_t> blob, uint32_t expected_n);

// Checks the blob against its stored checksum, then unpacks it.
StatusOr<PointSet> VerifyAndUnpack(std::span<const uint8_t> blob, uint32_t stored_crc,
                                   uint32_t expected_n);

}  // namespace alignset::storage

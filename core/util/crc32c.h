#pragma once

#include <cstdint>
#include <span>

namespace alignset {

// CRC-32C (Castagnoli, reflected polynomial 0x82F63B78, as in iSCSI, ext4 and
// LevelDB): the checksum of the cache's blobs and of table files. It detects
// every error burst of up to 32 bits and every odd number of flipped bits,
// and has published test vectors. `crc` continues an earlier call (start
// with 0).
uint32_t Crc32c(std::span<const uint8_t> data, uint32_t crc = 0);

}  // namespace alignset

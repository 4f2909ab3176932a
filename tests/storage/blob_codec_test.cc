#include "storage/blob_codec.h"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstring>
#include <limits>
#include <vector>

#include "core/util/hash.h"
#include "tests/storage/test_util.h"

namespace alignset::storage {
namespace {

// The bit-at-a-time definition of CRC-32C, to check the table-driven one.
uint32_t Crc32cBitwise(const std::vector<uint8_t>& data) {
  uint32_t c = 0xffffffffu;
  for (uint8_t b : data) {
    c ^= b;
    for (int i = 0; i < 8; ++i) c = (c >> 1) ^ ((c & 1u) ? 0x82F63B78u : 0u);
  }
  return ~c;
}

std::vector<uint8_t> Bytes(const char* s) { return std::vector<uint8_t>(s, s + std::strlen(s)); }

std::vector<uint8_t> RandomBytes(size_t n, uint64_t seed) {
  Pcg32 rng(seed);
  std::vector<uint8_t> v(n);
  for (uint8_t& b : v) b = static_cast<uint8_t>(rng.NextU32());
  return v;
}

TEST(Crc32c, PublishedTestVectors) {
  // The check value of the CRC catalogue and RFC 3720 appendix B.4.
  EXPECT_EQ(Crc32c(Bytes("123456789")), 0xE3069283u);
  EXPECT_EQ(Crc32c(std::vector<uint8_t>(32, 0x00)), 0x8A9136AAu);
  EXPECT_EQ(Crc32c(std::vector<uint8_t>(32, 0xFF)), 0x62A8AB43u);
  std::vector<uint8_t> up(32), down(32);
  for (int i = 0; i < 32; ++i) {
    up[i] = static_cast<uint8_t>(i);
    down[i] = static_cast<uint8_t>(31 - i);
  }
  EXPECT_EQ(Crc32c(up), 0x46DD794Eu);
  EXPECT_EQ(Crc32c(down), 0x113FDB5Cu);
  EXPECT_EQ(Crc32c({}), 0u);
}

TEST(Crc32c, SlicingMatchesBitwiseDefinitionAtEveryLengthAndAlignment) {
  const std::vector<uint8_t> data = RandomBytes(300, 11);
  for (size_t start = 0; start < 9; ++start) {
    for (size_t len = 0; start + len <= 140; ++len) {
      const std::vector<uint8_t> part(data.begin() + start, data.begin() + start + len);
      ASSERT_EQ(Crc32c(part), Crc32cBitwise(part)) << "start " << start << " len " << len;
    }
  }
}

TEST(Crc32c, IncrementalEqualsOneShot) {
  const std::vector<uint8_t> data = RandomBytes(1000, 5);
  const uint32_t whole = Crc32c(data);
  for (size_t cut = 0; cut <= data.size(); cut += 37) {
    const std::span<const uint8_t> all(data);
    EXPECT_EQ(Crc32c(all.subspan(cut), Crc32c(all.first(cut))), whole) << "cut " << cut;
  }
}

TEST(Crc32c, EverySingleBitFlipIsDetected) {
  std::vector<uint8_t> data = RandomBytes(256, 3);
  const uint32_t good = Crc32c(data);
  for (size_t byte = 0; byte < data.size(); ++byte) {
    for (int bit = 0; bit < 8; ++bit) {
      data[byte] ^= static_cast<uint8_t>(1u << bit);
      ASSERT_NE(Crc32c(data), good) << "byte " << byte << " bit " << bit;
      data[byte] ^= static_cast<uint8_t>(1u << bit);
    }
  }
}

TEST(PackPoints, LittleEndianFloat64XThenY) {
  // 0.5 = 0x3FE0000000000000, 0.25 = 0x3FD0000000000000.
  const std::vector<uint8_t> blob = PackPoints({{0.5, 0.25}});
  const std::vector<uint8_t> want = {0, 0, 0, 0, 0, 0, 0xE0, 0x3F, 0, 0, 0, 0, 0, 0, 0xD0, 0x3F};
  EXPECT_EQ(blob, want);
}

TEST(PackPoints, RoundTripIsBitExact) {
  PointSet pts = testing::MakePoints(testing::Key1(1000, 7), 1);
  pts[0] = {0.0, std::nextafter(1.0, 0.0)};
  pts[1] = {std::numeric_limits<double>::denorm_min(), 0.1};
  pts[2] = {std::numeric_limits<double>::min(), 1.0 / 3.0};
  const std::vector<uint8_t> blob = PackPoints(pts);
  ASSERT_EQ(blob.size(), pts.size() * kBytesPerPoint);
  auto back = UnpackPoints(blob, static_cast<uint32_t>(pts.size()));
  ASSERT_TRUE(back.ok()) << back.status().ToString();
  EXPECT_TRUE(testing::BitEqual(*back, pts));
}

TEST(UnpackPoints, WrongSizeIsDataLoss) {
  const std::vector<uint8_t> blob = PackPoints(testing::MakePoints(testing::Key1(16, 0), 0));
  EXPECT_EQ(UnpackPoints(blob, 17).status().code(), Status::Code::kDataLoss);
  const std::span<const uint8_t> cut(blob.data(), blob.size() - 1);
  EXPECT_EQ(UnpackPoints(cut, 16).status().code(), Status::Code::kDataLoss);
}

TEST(UnpackPoints, CoordinateOutsideUnitSquareIsDataLoss) {
  for (double bad : {1.0, -0.25, std::numeric_limits<double>::quiet_NaN(),
                     std::numeric_limits<double>::infinity()}) {
    const std::vector<uint8_t> blob = PackPoints({{0.5, 0.5}, {0.25, bad}});
    EXPECT_EQ(UnpackPoints(blob, 2).status().code(), Status::Code::kDataLoss) << bad;
  }
}

TEST(VerifyAndUnpack, ChecksumMismatchIsDataLoss) {
  const PointSet pts = testing::MakePoints(testing::Key1(64, 3), 2);
  std::vector<uint8_t> blob = PackPoints(pts);
  const uint32_t crc = Crc32c(blob);
  auto good = VerifyAndUnpack(blob, crc, 64);
  ASSERT_TRUE(good.ok());
  EXPECT_TRUE(testing::BitEqual(*good, pts));
  // A flip in the lowest mantissa bit keeps the point inside [0,1): only
  // the checksum can catch it.
  blob[8 * 5] ^= 0x01;
  ASSERT_TRUE(UnpackPoints(blob, 64).ok());
  EXPECT_EQ(VerifyAndUnpack(blob, crc, 64).status().code(), Status::Code::kDataLoss);
}

}  // namespace
}  // namespace alignset::storage

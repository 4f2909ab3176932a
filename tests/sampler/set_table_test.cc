// Table files: what goes in comes out bit for bit, every kind of bad file is
// refused with a message naming the problem, and a served set is the
// canonical one aligned as the server aligns it.
#include <alignset/set_table.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <string>

#include "core/align/canonical.h"
#include "core/optimize/aligned_lattice.h"
#include "core/util/crc32c.h"
#include "tests/sampler/table_fixture.h"

namespace alignset {
namespace {

using testing::LatticeSection;
using testing::PointsSection;

std::vector<uint8_t> Bytes(std::vector<TableSection> sections) {
  auto t = SetTable::FromSections(std::move(sections));
  EXPECT_TRUE(t.ok()) << t.status().message();
  return (*t)->Serialize();
}

// A changed byte with the checksum made right again: what a writer with a
// bug, not a damaged disk, would produce.
void Rechecksum(std::vector<uint8_t>* b) {
  const uint32_t c = Crc32c(std::span<const uint8_t>(b->data(), b->size() - 4));
  for (int i = 0; i < 4; ++i) (*b)[b->size() - 4 + i] = static_cast<uint8_t>(c >> (8 * i));
}

void Put32(std::vector<uint8_t>* b, size_t at, uint32_t v) {
  for (int i = 0; i < 4; ++i) (*b)[at + i] = static_cast<uint8_t>(v >> (8 * i));
}

void ExpectRefused(const std::vector<uint8_t>& b, Status::Code code, const std::string& says) {
  auto t = SetTable::Parse(b);
  ASSERT_FALSE(t.ok()) << "accepted; expected: " << says;
  EXPECT_EQ(t.status().code(), code) << t.status().message();
  EXPECT_NE(t.status().message().find(says), std::string::npos) << t.status().message();
}

class SetTableTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    lattice_ = new TableSection(LatticeSection(64, TableSpace::kOneDirection));
    pairs_ = new TableSection(LatticeSection(64, TableSpace::kTwoDirections));
  }
  static void TearDownTestSuite() {
    delete lattice_;
    delete pairs_;
  }
  static TableSection* lattice_;
  static TableSection* pairs_;
};
TableSection* SetTableTest::lattice_ = nullptr;
TableSection* SetTableTest::pairs_ = nullptr;

TEST_F(SetTableTest, WhatGoesInComesOutBitForBit) {
  const std::vector<TableSection> in = {*lattice_, *pairs_, PointsSection(32, TableSpace::kOneDirection),
                                        PointsSection(16, TableSpace::kOneQuarter)};
  const std::vector<uint8_t> bytes = Bytes(in);
  auto t = SetTable::Parse(bytes);
  ASSERT_TRUE(t.ok()) << t.status().message();
  ASSERT_EQ((*t)->sections().size(), in.size());
  for (size_t i = 0; i < in.size(); ++i) {
    const TableSection& a = in[i];
    const TableSection& b = (*t)->sections()[i];
    EXPECT_EQ(a.n, b.n);
    EXPECT_EQ(a.construction, b.construction);
    EXPECT_EQ(a.space, b.space);
    EXPECT_EQ(a.generators, b.generators);
    EXPECT_EQ(a.sets, b.sets);  // binary64 compared exactly
  }
  EXPECT_EQ((*t)->Serialize(), bytes);
  EXPECT_EQ((*t)->PointCounts("optimized"), (std::vector<uint32_t>{16, 32}));
  EXPECT_EQ((*t)->PointCounts("lattice"), (std::vector<uint32_t>{64}));
  // 46 generators of 4 bytes, and a header, a directory entry and a checksum.
  EXPECT_EQ(Bytes({*lattice_}).size(), 16u + 20u + 46u * 4u + 4u);
}

TEST_F(SetTableTest, SaveWritesAWholeFileThatLoads) {
  const std::string path = ::testing::TempDir() + "/alignset_table_test.tbl";
  auto t = SetTable::FromSections({*lattice_});
  ASSERT_TRUE(t.ok());
  ASSERT_TRUE((*t)->Save(path).ok());
  auto back = SetTable::Load(path);
  ASSERT_TRUE(back.ok()) << back.status().message();
  EXPECT_EQ((*back)->sections()[0].generators, lattice_->generators);
  std::ifstream tmp(path + ".tmp");
  EXPECT_FALSE(tmp.good());  // no temporary left behind
  std::remove(path.c_str());
  auto gone = SetTable::Load(path);
  EXPECT_EQ(gone.status().code(), Status::Code::kNotFound);
  EXPECT_NE(gone.status().message().find(path), std::string::npos);
}

TEST_F(SetTableTest, AnEmptyFileIsRefused) { ExpectRefused({}, Status::Code::kDataLoss, "empty file"); }

TEST_F(SetTableTest, ATruncatedFileIsRefusedWhereverItIsCut) {
  const std::vector<uint8_t> whole = Bytes({*lattice_, PointsSection(16, TableSpace::kOneDirection)});
  for (size_t keep : {size_t{9}, size_t{17}, size_t{40}, size_t{100}, whole.size() / 2, whole.size() - 1}) {
    SCOPED_TRACE(keep);
    ExpectRefused(std::vector<uint8_t>(whole.begin(), whole.begin() + keep), Status::Code::kDataLoss, "truncated");
  }
  std::vector<uint8_t> longer = whole;
  longer.push_back(0);
  ExpectRefused(longer, Status::Code::kDataLoss, "bytes after the table's end");
}

TEST_F(SetTableTest, AWrongMagicOrVersionIsRefused) {
  std::vector<uint8_t> b = Bytes({*lattice_});
  b[0] = 'X';
  ExpectRefused(b, Status::Code::kInvalidArgument, "wrong magic");
  ExpectRefused({'P', 'K', 3, 4}, Status::Code::kInvalidArgument, "wrong magic");
  b = Bytes({*lattice_});
  Put32(&b, 8, 3);
  Rechecksum(&b);
  ExpectRefused(b, Status::Code::kInvalidArgument, "format version 3; this library reads versions 1 to 2");
  b = Bytes({*lattice_});
  Put32(&b, 8, 0);
  Rechecksum(&b);
  ExpectRefused(b, Status::Code::kInvalidArgument, "format version 0;");
  // A version-1 file has no flags.
  b = Bytes({*lattice_});
  b[16 + 7] = 1;
  Rechecksum(&b);
  ExpectRefused(b, Status::Code::kInvalidArgument, "flags 1 this format version 1 does not have");
}

TEST_F(SetTableTest, AChecksumMismatchIsRefused) {
  std::vector<uint8_t> b = Bytes({*lattice_});
  b[16 + 20 + 5] ^= 0x01;  // a generator's bit
  ExpectRefused(b, Status::Code::kDataLoss, "checksum mismatch");
  b = Bytes({*lattice_});
  b.back() ^= 0x80;  // the checksum itself
  ExpectRefused(b, Status::Code::kDataLoss, "checksum mismatch");
}

TEST_F(SetTableTest, AnNOrKeyOutOfRangeIsRefused) {
  std::vector<uint8_t> b = Bytes({*lattice_});
  Put32(&b, 16, 8);  // N = 8 < 16
  Rechecksum(&b);
  ExpectRefused(b, Status::Code::kInvalidArgument, "N = 8 is below the minimum of 16 points");
  b = Bytes({*lattice_});
  Put32(&b, 16 + 20 + 4 * 7, 64);  // key 7's generator = N
  Rechecksum(&b);
  ExpectRefused(b, Status::Code::kInvalidArgument, "key 7: generator 64 out of range");
  b = Bytes({*lattice_});
  Put32(&b, 16 + 20 + 4 * 3, 2);  // not coprime to 64
  Rechecksum(&b);
  ExpectRefused(b, Status::Code::kInvalidArgument, "key 3: generator 2 out of range");
  b = Bytes({*lattice_});
  Put32(&b, 16 + 8, 45);  // a key short of the space's 46
  Rechecksum(&b);
  ExpectRefused(b, Status::Code::kInvalidArgument, "45 keys where the space has 46");
  b = Bytes({*lattice_});
  b[16 + 5] = 9;  // no such space
  Rechecksum(&b);
  ExpectRefused(b, Status::Code::kInvalidArgument, "unknown space 9");
  b = Bytes({*lattice_});
  b[16 + 4] = 42;  // no such construction
  Rechecksum(&b);
  ExpectRefused(b, Status::Code::kInvalidArgument, "unknown construction code 42");
  b = Bytes({PointsSection(16, TableSpace::kOneDirection)});
  const double outside = 1.0;
  std::memcpy(&b[16 + 20 + 8], &outside, 8);  // key 0, point 0's y
  Rechecksum(&b);
  ExpectRefused(b, Status::Code::kInvalidArgument, "key 0: point 0 is not in [0, 1)");
}

TEST_F(SetTableTest, SectionsMadeInMemoryAreCheckedAsAFilesAre) {
  TableSection short_one = *lattice_;
  short_one.generators.pop_back();
  EXPECT_EQ(SetTable::FromSections({short_one}).status().code(), Status::Code::kInvalidArgument);
  EXPECT_EQ(SetTable::FromSections({*lattice_, *lattice_}).status().code(), Status::Code::kInvalidArgument);
  EXPECT_EQ(SetTable::FromSections({}).status().code(), Status::Code::kInvalidArgument);
  TableSection unknown = *lattice_;
  unknown.construction = "sobol";
  EXPECT_NE(SetTable::FromSections({unknown}).status().message().find("unknown construction 'sobol'"),
            std::string::npos);
}

// The served lattice for any degree is the canonical key's, carried by the
// swap / mirror that carries the key onto the degree (the server's
// lattice_generator), and it scores for that degree exactly what the
// canonical lattice scores for its key.
TEST_F(SetTableTest, AServedLatticeIsTheCanonicalOneAligned) {
  auto t = SetTable::FromSections({*lattice_, *pairs_});
  ASSERT_TRUE(t.ok());
  for (int a : {0, 7, 30, 45, 46, 89, 90, 100, 135, 136, 179}) {
    SCOPED_TRACE(a);
    auto set = (*t)->Find(64, "lattice", {SetChoice::Kind::kOne, a, 0});
    ASSERT_TRUE(set.ok()) << set.status().message();
    const auto c = Canonicalize({static_cast<double>(a)});
    const uint32_t g = lattice_->generators[*CanonicalKeyIndex(c->key)];
    EXPECT_EQ(set->lattice_generator, MapLatticeGenerator(64, g, c->ops.swap, c->ops.invert, c->ops.invert_y));
    EXPECT_FALSE(set->folded);
    EXPECT_NEAR(*AlignedLatticeScore(64, set->lattice_generator, {static_cast<double>(a)}),
                *AlignedLatticeScore(64, g, {Phi1Degrees(c->key)}), 1e-9);
  }
  for (auto [a, b] : {std::pair{10, 100}, std::pair{12, 77}, std::pair{100, 170}}) {
    auto set = (*t)->Find(64, "lattice", {SetChoice::Kind::kTwo, a, b});
    ASSERT_TRUE(set.ok());
    const auto c = Canonicalize({static_cast<double>(a), static_cast<double>(b)});
    const uint32_t g = pairs_->generators[*CanonicalKeyIndex(c->key)];
    EXPECT_EQ(set->lattice_generator, MapLatticeGenerator(64, g, c->ops.swap, c->ops.invert, c->ops.invert_y));
  }
}

TEST_F(SetTableTest, AServedSetOfPointsIsTheCanonicalOneAligned) {
  const TableSection one = PointsSection(16, TableSpace::kOneDirection);
  const TableSection quarter = PointsSection(16, TableSpace::kOneQuarter);
  auto t = SetTable::FromSections({one, quarter});
  ASSERT_TRUE(t.ok());
  for (int a : {3, 60, 120, 170}) {
    auto set = (*t)->Find(16, "optimized", {SetChoice::Kind::kOne, a, 0});
    ASSERT_TRUE(set.ok());
    const auto c = Canonicalize({static_cast<double>(a)});
    EXPECT_EQ(*set->points, Align(one.sets[*CanonicalKeyIndex(c->key)], c->ops));
    EXPECT_EQ(set->lattice_generator, 0u);
  }
  // FindOne reads the quarter-degree section when there is one.
  auto q = (*t)->FindOne(16, "optimized", 120.3);
  ASSERT_TRUE(q.ok());
  const auto c = Canonicalize({120.25}, AngleGrid::kQuarterDegree);
  EXPECT_EQ(*q->points, Align(quarter.sets[*CanonicalKeyIndex(c->key, AngleGrid::kQuarterDegree)], c->ops));
}

TEST_F(SetTableTest, AMissingSectionIsAClearError) {
  auto t = SetTable::FromSections({*lattice_});
  ASSERT_TRUE(t.ok());
  auto pair = (*t)->Find(64, "lattice", {SetChoice::Kind::kTwo, 10, 100});
  EXPECT_EQ(pair.status().code(), Status::Code::kNotFound);
  EXPECT_NE(pair.status().message().find("no lattice sets of N = 64 for 2dir"), std::string::npos)
      << pair.status().message();
  EXPECT_EQ((*t)->Find(256, "lattice", {SetChoice::Kind::kOne, 10, 0}).status().code(), Status::Code::kNotFound);
  EXPECT_EQ((*t)->Find(64, "net", {SetChoice::Kind::kOne, 10, 0}).status().code(), Status::Code::kNotFound);
  EXPECT_EQ((*t)->Find(64, "lattice", {SetChoice::Kind::kOne, 180, 0}).status().code(),
            Status::Code::kInvalidArgument);
  EXPECT_EQ((*t)->Find(64, "lattice", {SetChoice::Kind::kFallback, 0, 0}).status().code(),
            Status::Code::kInvalidArgument);
}

// A section of some keys: the keys a render's pixels choose, of 4141 pairs.
TableSection SomeKeys(const TableSection& whole, std::vector<uint32_t> keys) {
  TableSection s = whole;
  s.keys = std::move(keys);
  s.generators.clear();
  s.sets.clear();
  for (uint32_t k : s.keys) {
    if (!whole.generators.empty()) s.generators.push_back(whole.generators[k]);
    if (!whole.sets.empty()) s.sets.push_back(whole.sets[k]);
  }
  return s;
}

uint32_t PairKey(int a, int b) {
  return static_cast<uint32_t>(*CanonicalKeyIndex(Canonicalize({static_cast<double>(a), static_cast<double>(b)})->key));
}

// A partial section serves what it holds exactly as the whole section does,
// refuses the rest with NOT_FOUND naming the pair, and needs version 2; a
// table of whole sections is still written as version 1, byte for byte.
TEST_F(SetTableTest, ASectionOfSomeKeysServesThemAsTheWholeSectionDoes) {
  const std::vector<uint32_t> held = {PairKey(10, 100), PairKey(12, 77), PairKey(30, 31)};
  std::vector<uint32_t> sorted = held;
  std::sort(sorted.begin(), sorted.end());
  sorted.erase(std::unique(sorted.begin(), sorted.end()), sorted.end());
  const TableSection points_whole = PointsSection(16, TableSpace::kTwoDirections);
  auto whole = SetTable::FromSections({*lattice_, *pairs_, points_whole});
  auto some = SetTable::FromSections({*lattice_, SomeKeys(*pairs_, sorted), SomeKeys(points_whole, sorted)});
  ASSERT_TRUE(whole.ok() && some.ok()) << some.status().message();
  for (auto [a, b] : {std::pair{10, 100}, std::pair{12, 77}, std::pair{30, 31}, std::pair{80, 170}}) {
    SCOPED_TRACE(std::to_string(a) + "," + std::to_string(b));
    const SetChoice pair{SetChoice::Kind::kTwo, a, b};
    for (const char* construction : {"lattice", "optimized"}) {
      const uint32_t n = std::string(construction) == "lattice" ? 64 : 16;
      const auto sections = (*some)->Resolve(n, construction);
      const bool held_pair = std::find(sorted.begin(), sorted.end(), PairKey(a, b)) != sorted.end();
      EXPECT_EQ((*some)->Holds(sections, pair), held_pair);
      auto from_some = (*some)->Find(sections, pair);
      auto from_whole = (*whole)->Find(n, construction, pair);
      ASSERT_TRUE(from_whole.ok());
      if (!held_pair) {
        EXPECT_EQ(from_some.status().code(), Status::Code::kNotFound);
        EXPECT_NE(from_some.status().message().find("2dir pair (80, 170)"), std::string::npos)
            << from_some.status().message();
        continue;
      }
      ASSERT_TRUE(from_some.ok()) << from_some.status().message();
      EXPECT_EQ(from_some->n, from_whole->n);
      EXPECT_EQ(from_some->lattice_generator, from_whole->lattice_generator);
      if (from_whole->points) {
        EXPECT_EQ(*from_some->points, *from_whole->points);
      }
    }
  }
  const std::vector<uint8_t> v2 = (*some)->Serialize();
  EXPECT_EQ(v2[8], 2);
  auto back = SetTable::Parse(v2);
  ASSERT_TRUE(back.ok()) << back.status().message();
  EXPECT_EQ((*back)->sections()[1].keys, sorted);
  EXPECT_EQ((*back)->sections()[1].generators, SomeKeys(*pairs_, sorted).generators);
  EXPECT_EQ((*back)->sections()[2].sets, SomeKeys(points_whole, sorted).sets);
  EXPECT_EQ((*back)->Serialize(), v2);
  EXPECT_EQ((*some)->format_version(), 2u);
  EXPECT_EQ((*whole)->format_version(), 1u);
  EXPECT_EQ((*whole)->Serialize()[8], 1);
  // One encoding: whole sections under a version-2 header are refused.
  std::vector<uint8_t> relabelled = (*whole)->Serialize();
  Put32(&relabelled, 8, 2);
  Rechecksum(&relabelled);
  ExpectRefused(relabelled, Status::Code::kInvalidArgument, "are all whole (written as version 1)");
  // Keys out of the space, repeated or out of order are refused, in memory
  // and in a file.
  for (std::vector<uint32_t> bad : {std::vector<uint32_t>{4141}, std::vector<uint32_t>{7, 7},
                                    std::vector<uint32_t>{9, 3}}) {
    TableSection s = SomeKeys(*pairs_, {1, 2});
    s.keys = bad;
    s.generators.resize(bad.size(), 1);
    EXPECT_EQ(SetTable::FromSections({s}).status().code(), Status::Code::kInvalidArgument);
  }
  std::vector<uint8_t> b = Bytes({SomeKeys(*pairs_, {3, 9})});
  Put32(&b, 16 + 20, 9);  // keys 9, 9
  Rechecksum(&b);
  ExpectRefused(b, Status::Code::kInvalidArgument, "keys not ascending (9 after 9)");
}

// A lattice section whose keys have fewer points than N (a render's size
// span) serves each key's lattice at its own size, and keeps the sizes
// through a file.
TEST_F(SetTableTest, ALatticeOfFewerPointsThanNKeepsItsSize) {
  TableSection sized = *lattice_;
  sized.sizes.assign(sized.generators.size(), 64);
  const uint32_t key = 5;
  sized.sizes[key] = 61;  // prime: any generator below it is coprime
  sized.generators[key] = 17;
  auto t = SetTable::FromSections({sized});
  ASSERT_TRUE(t.ok()) << t.status().message();
  for (int a = 0; a < 180; ++a) {
    const auto c = Canonicalize({static_cast<double>(a)});
    const uint32_t k = static_cast<uint32_t>(*CanonicalKeyIndex(c->key));
    auto set = (*t)->Find(64, "lattice", {SetChoice::Kind::kOne, a, 0});
    ASSERT_TRUE(set.ok());
    EXPECT_EQ(set->n, sized.sizes[k]);
    EXPECT_EQ(set->lattice_generator,
              MapLatticeGenerator(sized.sizes[k], sized.generators[k], c->ops.swap, c->ops.invert, c->ops.invert_y));
  }
  auto back = SetTable::Parse((*t)->Serialize());
  ASSERT_TRUE(back.ok()) << back.status().message();
  EXPECT_EQ((*back)->sections()[0].sizes, sized.sizes);
  TableSection too_big = sized;
  too_big.sizes[key] = 65;
  EXPECT_NE(SetTable::FromSections({too_big}).status().message().find("size 65 above N"), std::string::npos);
  TableSection too_small = sized;
  too_small.sizes[key] = 8;
  too_small.generators[key] = 3;
  EXPECT_NE(SetTable::FromSections({too_small}).status().message().find("size 8: N = 8 is below"), std::string::npos)
      << SetTable::FromSections({too_small}).status().message();
  TableSection points = PointsSection(16, TableSpace::kOneDirection);
  points.sizes.assign(points.sets.size(), 16);
  EXPECT_EQ(SetTable::FromSections({points}).status().code(), Status::Code::kInvalidArgument);
}

}  // namespace
}  // namespace alignset

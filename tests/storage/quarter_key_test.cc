// Quarter-degree keys next to whole-degree ones: one column, old rows kept.
#include <gtest/gtest.h>

#include "storage/set_cache.h"
#include "test_util.h"

namespace alignset::storage::testing {
namespace {

SetKey Quarter(uint32_t n, int phi, int quarter) {
  SetKey k = Key1(n, phi);
  k.dirs.phi1_quarter = quarter;
  return k;
}

TEST(QuarterKeys, RoundTripBesideWholeDegreesWithTheirOwnRows) {
  TempDir dir;
  auto cache = MustOpen(dir.File("c.sqlite"));
  const SetKey whole = Key1(64, 30), q1 = Quarter(64, 30, 1), q3 = Quarter(64, 30, 3);
  SetRecord a = MakeRecord(whole, 1), b = MakeRecord(q1, 2), c = MakeRecord(q3, 3);
  b.points[0] = {0.125, 0.5};  // distinct blobs even where MakePoints ignores the quarter
  c.points[0] = {0.375, 0.5};
  ASSERT_TRUE(cache->Put(a).ok());
  ASSERT_TRUE(cache->Put(b).ok());
  ASSERT_TRUE(cache->Put(c).ok());
  ASSERT_TRUE(cache->Put(MakeRecord(Key1(64, 31), 4)).ok());
  EXPECT_EQ(cache->Get(whole)->iterations, 1);
  EXPECT_EQ(cache->Get(q1)->iterations, 2);
  EXPECT_EQ(cache->Get(q3)->iterations, 3);
  EXPECT_TRUE(BitEqual(cache->Get(q1)->points, b.points));
  EXPECT_EQ(cache->Get(Quarter(64, 30, 2)).status().code(), Status::Code::kNotFound);
  // Listed in angle order: 30, 30.25, 30.75, 31.
  auto all = cache->List();
  ASSERT_TRUE(all.ok());
  const std::vector<SetKey> want = {whole, q1, q3, Key1(64, 31)};
  EXPECT_EQ(*all, want);
  EXPECT_EQ(cache->Stats()->one_direction_sets, 4);
  EXPECT_EQ(cache->Verify()->corrupt.size(), 0u);
  EXPECT_EQ(KeyToString(q1), "n=64 dirs=1:30.25 profile=0123456789abcdef");

  // Whole degrees stay INTEGERs in the file, exactly as an older alignset
  // wrote them; quarters are REALs.
  cache.reset();
  RawDb raw(dir.File("c.sqlite"));
  EXPECT_EQ(raw.Text("SELECT typeof(phi1) FROM sets WHERE phi1 = 30"), "integer");
  EXPECT_EQ(raw.Text("SELECT typeof(phi1) FROM sets WHERE phi1 = 30.25"), "real");
  EXPECT_EQ(raw.Int("SELECT COUNT(*) FROM sets WHERE phi1 = 30"), 1);
}

TEST(QuarterKeys, ARowWrittenTheOldWayIsStillTheWholeDegreeKey) {
  // A whole-degree row as the 46-key service stored it (phi1 bound as an
  // integer) is found by the same key today, and merges into a new cache.
  TempDir dir;
  {
    auto cache = MustOpen(dir.File("old.sqlite"));
    ASSERT_TRUE(cache->Put(MakeRecord(Key1(128, 12), 7)).ok());
  }
  {
    RawDb raw(dir.File("old.sqlite"));
    ASSERT_EQ(raw.Text("SELECT typeof(phi1) FROM sets"), "integer");
  }
  auto fresh = MustOpen(dir.File("new.sqlite"));
  auto merged = fresh->MergeFrom(dir.File("old.sqlite"));
  ASSERT_TRUE(merged.ok()) << merged.status().ToString();
  EXPECT_EQ(merged->added, 1);
  EXPECT_EQ(fresh->Get(Key1(128, 12))->iterations, 7);
  ASSERT_TRUE(fresh->Put(MakeRecord(Quarter(128, 12, 2), 8)).ok());
  EXPECT_EQ(fresh->List()->size(), 2u);
}

TEST(QuarterKeys, InvalidQuartersAreRefused) {
  EXPECT_FALSE(ValidateKey(Quarter(64, 45, 1)).ok());
  EXPECT_FALSE(ValidateKey(Quarter(64, 10, 4)).ok());
  EXPECT_FALSE(ValidateKey(Quarter(64, 10, -1)).ok());
  SetKey two = Key2(64, 10, 20);
  two.dirs.phi1_quarter = 1;
  EXPECT_FALSE(ValidateKey(two).ok());
  EXPECT_TRUE(ValidateKey(Quarter(64, 44, 3)).ok());
  // A row whose angle is not on the quarter grid (not written by alignset)
  // reads as corrupt, never as a neighbouring key.
  TempDir dir;
  {
    auto cache = MustOpen(dir.File("c.sqlite"));
    ASSERT_TRUE(cache->Put(MakeRecord(Quarter(64, 20, 1), 1)).ok());
  }
  {
    RawDb raw(dir.File("c.sqlite"));
    ASSERT_TRUE(raw.Exec("UPDATE sets SET phi1 = 20.3"));
  }
  auto cache = MustOpen(dir.File("c.sqlite"));
  EXPECT_EQ(cache->Verify()->corrupt.size(), 1u);
  EXPECT_EQ(cache->Get(Quarter(64, 20, 1)).status().code(), Status::Code::kNotFound);
}

}  // namespace
}  // namespace alignset::storage::testing

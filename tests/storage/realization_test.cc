// Realizations in the cache (issue 15): part of the key, existing rows of an
// older file become realization 0, and shards from older files merge as such.
#include <gtest/gtest.h>

#include "storage/blob_codec.h"
#include "storage/schema.h"
#include "storage/set_cache.h"
#include "tests/storage/test_util.h"

namespace alignset::storage {
namespace {

using testing::Key1;
using testing::MakeRecord;
using testing::TempDir;
using testing::WithRealization;

// A cache file as a build before realizations wrote it (schema version 2),
// holding `rec` as its only set.
void WriteVersionTwoFile(const std::string& path, const SetRecord& rec) {
  auto db = Db::Open(path, SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE, 1000);
  ASSERT_TRUE(db.ok());
  ASSERT_TRUE(Migrate(*db, {Migrations()[0], Migrations()[1]}).ok());
  auto ins = Stmt::Prepare(db->get(),
                           "INSERT INTO sets VALUES (?1, 1, ?2, ?2, ?3, 1.5, 0.5, 0.1, 4, 1.25, "
                           "'fast', 1700000004, 2, ?4, ?5)");
  ASSERT_TRUE(ins.ok());
  const std::vector<uint8_t> blob = PackPoints(rec.points);
  ins->BindInt(1, rec.key.n);
  ins->BindInt(2, rec.key.dirs.phi1);
  ins->BindText(3, rec.key.profile);
  ins->BindInt(4, Crc32c(blob));
  ins->BindBlob(5, blob);
  ASSERT_TRUE(ins->Run().ok());
}

TEST(Realizations, ArePartOfTheKey) {
  TempDir dir;
  auto cache = SetCache::Open(dir.File("c.sqlite"));
  ASSERT_TRUE(cache.ok());
  const SetRecord r0 = MakeRecord(Key1(64, 30), 1);
  const SetRecord r5 = MakeRecord(WithRealization(Key1(64, 30), 5), 2);
  ASSERT_TRUE((*cache)->Put(r0).ok());
  EXPECT_EQ((*cache)->Get(r5.key).status().code(), Status::Code::kNotFound);
  ASSERT_TRUE((*cache)->Put(r5).ok());
  auto got0 = (*cache)->Get(r0.key);
  auto got5 = (*cache)->Get(r5.key);
  ASSERT_TRUE(got0.ok() && got5.ok());
  EXPECT_TRUE(testing::BitEqual(got0->points, r0.points));
  EXPECT_TRUE(testing::BitEqual(got5->points, r5.points));
  EXPECT_EQ(got5->key.realization, 5u);
  auto keys = (*cache)->List(64u);
  ASSERT_TRUE(keys.ok());
  ASSERT_EQ(keys->size(), 2u);
  EXPECT_EQ((*keys)[1].realization, 5u);
  EXPECT_EQ(KeyToString(r5.key), "n=64 dirs=1:30 r=5 profile=0123456789abcdef");
  EXPECT_EQ(KeyToString(r0.key), "n=64 dirs=1:30 profile=0123456789abcdef");
  // Beyond the documented maximum: refused.
  EXPECT_EQ((*cache)->Put(MakeRecord(WithRealization(Key1(64, 30), kMaxRealization + 1))).code(),
            Status::Code::kInvalidArgument);
}

TEST(Realizations, RowsOfAnOlderFileBecomeRealizationZero) {
  TempDir dir;
  const std::string path = dir.File("old.sqlite");
  const SetRecord rec = MakeRecord(Key1(128, 9), 4);
  WriteVersionTwoFile(path, rec);
  auto cache = SetCache::Open(path);
  ASSERT_TRUE(cache.ok()) << cache.status().ToString();
  auto got = (*cache)->Get(rec.key);  // realization 0
  ASSERT_TRUE(got.ok()) << got.status().ToString();
  EXPECT_TRUE(testing::BitEqual(got->points, rec.points));
  EXPECT_EQ((*cache)->Get(WithRealization(rec.key, 1)).status().code(), Status::Code::kNotFound);
  ASSERT_TRUE((*cache)->Put(MakeRecord(WithRealization(rec.key, 1), 5)).ok());
  EXPECT_EQ((*cache)->Stats()->sets, 2);
  auto report = (*cache)->Verify();
  ASSERT_TRUE(report.ok());
  EXPECT_EQ(report->checked, 2);
  EXPECT_TRUE(report->corrupt.empty());
}

TEST(Realizations, AShardFromAnOlderBuildMergesAsRealizationZero) {
  TempDir dir;
  const SetRecord rec = MakeRecord(Key1(256, 40), 7);
  const std::string old = dir.File("old-shard.sqlite");
  WriteVersionTwoFile(old, rec);
  auto cache = SetCache::Open(dir.File("new.sqlite"));
  ASSERT_TRUE(cache.ok());
  ASSERT_TRUE((*cache)->Put(MakeRecord(WithRealization(rec.key, 2), 8)).ok());
  auto merged = (*cache)->MergeFrom(old);
  ASSERT_TRUE(merged.ok()) << merged.status().ToString();
  EXPECT_EQ(merged->added, 1);
  auto got = (*cache)->Get(rec.key);
  ASSERT_TRUE(got.ok());
  EXPECT_TRUE(testing::BitEqual(got->points, rec.points));
}

}  // namespace
}  // namespace alignset::storage

#include "storage/schema.h"

#include <gtest/gtest.h>

#include <fstream>

#include "storage/blob_codec.h"
#include "storage/set_cache.h"
#include "tests/storage/test_util.h"

namespace alignset::storage {
namespace {

using testing::Key1;
using testing::MakeRecord;
using testing::RawDb;
using testing::TempDir;

Db MustOpenRaw(const std::string& path) {
  auto db = Db::Open(path, SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE, 1000);
  EXPECT_TRUE(db.ok()) << db.status().ToString();
  return std::move(db).value();
}

int Version(const std::string& path) {
  auto db = Db::Open(path, SQLITE_OPEN_READONLY, 1000);
  if (!db.ok()) return -1;
  auto v = SchemaVersion(*db);
  return v.ok() ? *v : -1;
}

TEST(Schema, StepsAreNumberedOneToLatest) {
  const auto& steps = Migrations();
  ASSERT_FALSE(steps.empty());
  for (size_t i = 0; i < steps.size(); ++i) EXPECT_EQ(steps[i].version, static_cast<int>(i) + 1);
  EXPECT_EQ(LatestSchemaVersion(), static_cast<int>(steps.size()));
}

TEST(Schema, EmptyFileMigratesToLatest) {
  TempDir dir;
  const std::string path = dir.File("c.sqlite");
  std::ofstream(path).close();  // zero bytes: SQLite's empty database
  ASSERT_EQ(Version(path), 0);
  {
    auto cache = SetCache::Open(path);
    ASSERT_TRUE(cache.ok()) << cache.status().ToString();
    ASSERT_TRUE((*cache)->Put(MakeRecord(Key1(64, 1))).ok());
  }
  EXPECT_EQ(Version(path), LatestSchemaVersion());
  RawDb raw(path);
  EXPECT_EQ(raw.Int("SELECT COUNT(*) FROM schema_version"), LatestSchemaVersion());
  EXPECT_EQ(raw.Int("SELECT COUNT(*) FROM sqlite_master WHERE name = 'sets_by_profile'"), 1);
}

TEST(Schema, VersionZeroFileWithOtherTablesMigratesAndKeepsThem) {
  TempDir dir;
  const std::string path = dir.File("c.sqlite");
  {
    RawDb raw(path);
    ASSERT_TRUE(raw.Exec("CREATE TABLE notes (t TEXT); INSERT INTO notes VALUES ('kept')"));
  }
  ASSERT_EQ(Version(path), 0);
  ASSERT_TRUE(SetCache::Open(path).ok());
  EXPECT_EQ(Version(path), LatestSchemaVersion());
  RawDb raw(path);
  EXPECT_EQ(raw.Text("SELECT t FROM notes"), "kept");
}

TEST(Schema, OlderVersionMigratesAndKeepsItsSets) {
  TempDir dir;
  const std::string path = dir.File("c.sqlite");
  const SetRecord rec = MakeRecord(Key1(128, 9), 4);
  {
    Db db = MustOpenRaw(path);
    ASSERT_TRUE(Migrate(db, {Migrations()[0]}).ok());
    // A set written by a version-1 build.
    auto ins = Stmt::Prepare(db.get(),
                             "INSERT INTO sets VALUES (128, 1, 9, 9, ?1, 1.5, 0.5, 0.1, 4, 1.25, "
                             "'direct', 1700000004, 1, ?2, ?3)");
    ASSERT_TRUE(ins.ok());
    const std::vector<uint8_t> blob = PackPoints(rec.points);
    ins->BindText(1, rec.key.profile);
    ins->BindInt(2, Crc32c(blob));
    ins->BindBlob(3, blob);
    ASSERT_TRUE(ins->Run().ok());
  }
  ASSERT_EQ(Version(path), 1);
  auto cache = SetCache::Open(path);
  ASSERT_TRUE(cache.ok()) << cache.status().ToString();
  EXPECT_EQ(Version(path), LatestSchemaVersion());
  auto got = (*cache)->Get(rec.key);
  ASSERT_TRUE(got.ok()) << got.status().ToString();
  EXPECT_TRUE(testing::BitEqual(got->points, rec.points));
  EXPECT_EQ(got->iterations, 4);
}

TEST(Schema, ReopeningIsIdempotent) {
  TempDir dir;
  const std::string path = dir.File("c.sqlite");
  const SetRecord rec = MakeRecord(Key1(64, 2));
  ASSERT_TRUE((*SetCache::Open(path))->Put(rec).ok());
  std::string history;
  {
    RawDb raw(path);
    history = raw.Text("SELECT group_concat(version || ':' || applied_unix, ',') FROM schema_version");
  }
  for (int i = 0; i < 3; ++i) {
    auto cache = SetCache::Open(path);
    ASSERT_TRUE(cache.ok());
    EXPECT_EQ((*cache)->Stats()->sets, 1);
  }
  RawDb raw(path);
  EXPECT_EQ(raw.Text("SELECT group_concat(version || ':' || applied_unix, ',') FROM schema_version"),
            history);
  EXPECT_EQ(raw.Int("SELECT COUNT(*) FROM schema_version"), LatestSchemaVersion());
}

TEST(Schema, NewerFileIsRefusedAndLeftAlone) {
  TempDir dir;
  const std::string path = dir.File("c.sqlite");
  ASSERT_TRUE(SetCache::Open(path).ok());
  {
    RawDb raw(path);
    ASSERT_TRUE(raw.Exec("INSERT INTO schema_version VALUES (99, 0, 'from the future')"));
  }
  auto cache = SetCache::Open(path);
  EXPECT_EQ(cache.status().code(), Status::Code::kInvalidArgument);
  SetCache::Options ro;
  ro.read_only = true;
  EXPECT_EQ(SetCache::Open(path, ro).status().code(), Status::Code::kInvalidArgument);
  EXPECT_EQ(Version(path), 99);
}

TEST(Schema, FailingStepRollsBackWholly) {
  TempDir dir;
  const std::string path = dir.File("c.sqlite");
  Db db = MustOpenRaw(path);
  std::vector<Migration> steps = Migrations();
  steps.push_back({static_cast<int>(steps.size()) + 1, "broken",
                   "CREATE TABLE half_done (x); INSERT INTO no_such_table VALUES (1);"});
  EXPECT_FALSE(Migrate(db, steps).ok());
  // The good steps stay applied, the broken one leaves no trace.
  EXPECT_EQ(*SchemaVersion(db), LatestSchemaVersion());
  RawDb raw(path);
  EXPECT_EQ(raw.Int("SELECT COUNT(*) FROM sqlite_master WHERE name = 'half_done'"), 0);
}

TEST(Schema, StepsOutOfOrderAreRejected) {
  TempDir dir;
  Db db = MustOpenRaw(dir.File("c.sqlite"));
  EXPECT_FALSE(Migrate(db, {Migrations()[1]}).ok());
  EXPECT_EQ(*SchemaVersion(db), 0);
}

}  // namespace
}  // namespace alignset::storage

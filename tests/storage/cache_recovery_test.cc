// Page-level damage (storage/cache_recovery.h): a damaged B-tree page is
// found, its rows listed by key, and every other set copied out intact.
#include "storage/cache_recovery.h"

#include <gtest/gtest.h>

#include <map>

#include "storage/set_rows.h"
#include "tests/damage_pages.h"
#include "tests/storage/test_util.h"

namespace alignset::storage {
namespace {

using testing::Key1;
using testing::Key2;
using testing::MakeRecord;
using testing::MustOpen;
using testing::TempDir;

// 46 + 60 + 10 small sets (N = 64: a few rows per 4 KiB page, so the table has
// many leaves); returns rowid -> key.
std::map<int64_t, SetKey> Fill(const std::string& path) {
  {
    auto cache = MustOpen(path);
    for (int phi = 0; phi <= 45; ++phi) EXPECT_TRUE(cache->Put(MakeRecord(Key1(64, phi))).ok());
    for (int phi = 0; phi < 60; ++phi) EXPECT_TRUE(cache->Put(MakeRecord(Key2(64, phi, phi + 50))).ok());
    for (int phi = 0; phi < 10; ++phi) {  // realizations are part of the key
      SetKey k = Key1(64, phi);
      k.realization = 3;
      EXPECT_TRUE(cache->Put(MakeRecord(k)).ok());
    }
  }  // closed: checkpointed, no WAL left
  std::map<int64_t, SetKey> keys;
  auto db = Db::Open(path, SQLITE_OPEN_READONLY, 1000);
  auto stmt = Stmt::Prepare(db->get(), std::string("SELECT ") + kKeyColumns + ", rowid FROM sets");
  while (*stmt->Step()) keys[stmt->Int(6)] = KeyFromRow(*stmt);
  return keys;
}

TEST(CacheRecovery, CleanFileHasNoDamage) {
  TempDir dir;
  const auto keys = Fill(dir.File("c.sqlite"));
  auto check = QuickCheck(dir.File("c.sqlite"));
  ASSERT_TRUE(check.ok()) << check.status().message();
  EXPECT_TRUE(check->empty());
  auto scan = ScanForDamage(dir.File("c.sqlite"));
  ASSERT_TRUE(scan.ok());
  EXPECT_EQ(scan->readable, static_cast<int64_t>(keys.size()));
  EXPECT_TRUE(scan->damaged.empty());
}

TEST(CacheRecovery, DamagedLeafIsFoundListedByKeyAndTheRestRecovered) {
  TempDir dir;
  const std::string path = dir.File("c.sqlite");
  const auto keys = Fill(path);
  const ::alignset::testing::TablePages pages = ::alignset::testing::FindTablePages(path, "sets");
  ASSERT_GT(pages.leaves.size(), 4u);
  const size_t victim = pages.leaves.size() / 2;  // a leaf in the middle
  ::alignset::testing::DamagePageHeader(path, pages.page_size, pages.leaves[victim]);
  std::set<std::string> expected;
  for (int64_t rowid : pages.rowids[victim]) expected.insert(KeyToString(keys.at(rowid)));
  ASSERT_FALSE(expected.empty());

  auto check = QuickCheck(path);
  ASSERT_TRUE(check.ok()) << check.status().message();
  EXPECT_FALSE(check->empty());

  // The old Verify stopped at the damaged page; now every row is accounted for.
  auto cache = MustOpen(path, {.read_only = true});
  auto verify = cache->Verify();
  ASSERT_TRUE(verify.ok()) << verify.status().message();
  EXPECT_EQ(verify->checked, static_cast<int64_t>(keys.size()));
  std::set<std::string> listed;
  for (const SetKey& k : verify->corrupt) listed.insert(KeyToString(k));
  EXPECT_EQ(listed, expected);
  EXPECT_FALSE(verify->problems.empty());

  // Stats no longer fail with DATA_LOSS: they count what can be read.
  auto stats = cache->Stats();
  ASSERT_TRUE(stats.ok()) << stats.status().message();
  EXPECT_TRUE(stats->damaged);
  EXPECT_EQ(stats->sets, static_cast<int64_t>(keys.size() - expected.size()));

  auto report = RecoverCache(path, dir.File("new.sqlite"));
  ASSERT_TRUE(report.ok()) << report.status().message();
  EXPECT_EQ(report->recovered, static_cast<int64_t>(keys.size() - expected.size()));
  EXPECT_EQ(report->lost.size(), expected.size());
  auto fresh = MustOpen(dir.File("new.sqlite"), {.read_only = true});
  auto clean = fresh->Verify();
  ASSERT_TRUE(clean.ok());
  EXPECT_TRUE(clean->corrupt.empty());
  EXPECT_EQ(clean->checked, report->recovered);
  EXPECT_TRUE(QuickCheck(dir.File("new.sqlite"))->empty());
  for (const auto& [rowid, key] : keys) {
    auto rec = fresh->Get(key);
    if (expected.count(KeyToString(key))) {
      EXPECT_EQ(rec.status().code(), Status::Code::kNotFound);
    } else {
      ASSERT_TRUE(rec.ok()) << KeyToString(key);
      EXPECT_TRUE(testing::BitEqual(rec->points, MakeRecord(key).points));
    }
  }
}

TEST(CacheRecovery, DamagedRootLeavesTheKeysTheIndexesStillName) {
  TempDir dir;
  const std::string path = dir.File("c.sqlite");
  const auto keys = Fill(path);
  const auto pages = ::alignset::testing::FindTablePages(path, "sets");
  ::alignset::testing::DamagePageHeader(path, pages.page_size, pages.root);
  auto scan = ScanForDamage(path);
  ASSERT_TRUE(scan.ok()) << scan.status().message();
  EXPECT_EQ(scan->readable, 0);
  EXPECT_EQ(scan->damaged.size(), keys.size());  // every key, from the indexes
}

TEST(CacheRecovery, RecoverRefusesAnExistingPartialFileUnlessForced) {
  TempDir dir;
  Fill(dir.File("c.sqlite"));
  { std::ofstream(dir.File("new.sqlite.partial")) << "someone else's work"; }
  auto refused = RecoverCache(dir.File("c.sqlite"), dir.File("new.sqlite"));
  ASSERT_FALSE(refused.ok());
  EXPECT_NE(refused.status().message().find("--force"), std::string::npos);
  EXPECT_TRUE(std::filesystem::exists(dir.File("new.sqlite.partial")));
  auto forced = RecoverCache(dir.File("c.sqlite"), dir.File("new.sqlite"), /*overwrite_partial=*/true);
  ASSERT_TRUE(forced.ok()) << forced.status().message();
  EXPECT_EQ(forced->recovered, 116);
  EXPECT_FALSE(RecoverCache(dir.File("c.sqlite"), dir.File("new.sqlite")).ok());  // exists now
}

}  // namespace
}  // namespace alignset::storage

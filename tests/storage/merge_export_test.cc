#include <gtest/gtest.h>

#include <atomic>
#include <filesystem>
#include <fstream>
#include <thread>

#include "storage/set_cache.h"
#include "tests/storage/test_util.h"

namespace alignset::storage {
namespace {

using testing::BitEqual;
using testing::Key1;
using testing::Key2;
using testing::MakeRecord;
using testing::MustOpen;
using testing::RawDb;
using testing::TempDir;

// Writes a shard holding `keys`, each at generation `gen`.
void WriteShard(const std::string& path, const std::vector<SetKey>& keys, int gen) {
  auto shard = MustOpen(path);
  for (const SetKey& k : keys) ASSERT_TRUE(shard->Put(MakeRecord(k, gen)).ok());
}

TEST(MergeFrom, DisjointShardsAddEverything) {
  TempDir dir;
  const std::vector<SetKey> a = {Key1(64, 0), Key1(64, 1), Key2(128, 0, 90)};
  const std::vector<SetKey> b = {Key1(256, 45), Key2(64, 10, 20), Key1(64, 2, "p2")};
  WriteShard(dir.File("a.sqlite"), a, 1);
  WriteShard(dir.File("b.sqlite"), b, 2);
  auto main = MustOpen(dir.File("main.sqlite"));
  auto ra = main->MergeFrom(dir.File("a.sqlite"));
  ASSERT_TRUE(ra.ok()) << ra.status().ToString();
  EXPECT_EQ(ra->added, 3);
  EXPECT_EQ(ra->skipped_existing, 0);
  EXPECT_EQ(ra->skipped_corrupt, 0);
  auto rb = main->MergeFrom(dir.File("b.sqlite"));
  ASSERT_TRUE(rb.ok());
  EXPECT_EQ(rb->added, 3);
  EXPECT_EQ(main->Stats()->sets, 6);
  for (const SetKey& k : a) EXPECT_TRUE(BitEqual(main->Get(k)->points, MakeRecord(k, 1).points));
  for (const SetKey& k : b) EXPECT_TRUE(BitEqual(main->Get(k)->points, MakeRecord(k, 2).points));
  EXPECT_EQ(main->Get(b[0])->iterations, 2);  // metadata travels with the set
  // Merging again adds nothing.
  auto again = main->MergeFrom(dir.File("a.sqlite"));
  EXPECT_EQ(again->added, 0);
  EXPECT_EQ(again->skipped_existing, 3);
}

TEST(MergeFrom, OverlappingShardKeepsWhatTheCacheHas) {
  TempDir dir;
  const std::vector<SetKey> a = {Key1(64, 0), Key1(64, 1), Key1(64, 2)};
  const std::vector<SetKey> b = {Key1(64, 1), Key1(64, 2), Key1(64, 3)};
  WriteShard(dir.File("a.sqlite"), a, 1);
  WriteShard(dir.File("b.sqlite"), b, 2);
  auto main = MustOpen(dir.File("main.sqlite"));
  ASSERT_EQ(main->MergeFrom(dir.File("a.sqlite"))->added, 3);
  auto r = main->MergeFrom(dir.File("b.sqlite"));
  ASSERT_TRUE(r.ok());
  EXPECT_EQ(r->added, 1);
  EXPECT_EQ(r->skipped_existing, 2);
  EXPECT_EQ(main->Stats()->sets, 4);
  EXPECT_EQ(main->Get(Key1(64, 1))->iterations, 1);  // a's copy stays
  EXPECT_EQ(main->Get(Key1(64, 3))->iterations, 2);
}

TEST(MergeFrom, CorruptShardRowsAreSkipped) {
  TempDir dir;
  const std::vector<SetKey> keys = {Key1(1024, 0), Key1(1024, 1), Key1(1024, 2)};
  WriteShard(dir.File("a.sqlite"), keys, 1);
  {
    RawDb raw(dir.File("a.sqlite"));
    ASSERT_TRUE(raw.FlipBlobByte(keys[1], 9000));
  }
  auto main = MustOpen(dir.File("main.sqlite"));
  auto r = main->MergeFrom(dir.File("a.sqlite"));
  ASSERT_TRUE(r.ok());
  EXPECT_EQ(r->added, 2);
  EXPECT_EQ(r->skipped_corrupt, 1);
  EXPECT_EQ(main->Get(keys[1]).status().code(), Status::Code::kNotFound);
  EXPECT_TRUE(main->Verify()->corrupt.empty());
}

TEST(MergeFrom, VerifiedCopyReplacesACorruptRowOfOurs) {
  TempDir dir;
  const SetKey key = Key2(512, 30, 60);
  WriteShard(dir.File("a.sqlite"), {key}, 1);
  auto main = MustOpen(dir.File("main.sqlite"));
  ASSERT_TRUE(main->Put(MakeRecord(key, 1)).ok());
  {
    RawDb raw(dir.File("main.sqlite"));
    ASSERT_TRUE(raw.FlipBlobByte(key, 100, 0x10));
  }
  ASSERT_EQ(main->Get(key).status().code(), Status::Code::kDataLoss);
  auto r = main->MergeFrom(dir.File("a.sqlite"));
  ASSERT_TRUE(r.ok());
  EXPECT_EQ(r->added, 1);
  ASSERT_TRUE(main->Get(key).ok());
  EXPECT_TRUE(BitEqual(main->Get(key)->points, MakeRecord(key, 1).points));
}

TEST(MergeFrom, BadSourcesAreErrors) {
  TempDir dir;
  auto main = MustOpen(dir.File("main.sqlite"));
  EXPECT_EQ(main->MergeFrom(dir.File("missing.sqlite")).status().code(), Status::Code::kNotFound);
  std::ofstream(dir.File("junk")) << std::string(5000, 'j');
  EXPECT_FALSE(main->MergeFrom(dir.File("junk")).ok());
  {
    RawDb raw(dir.File("other.sqlite"));
    ASSERT_TRUE(raw.Exec("CREATE TABLE t (x)"));
  }
  EXPECT_EQ(main->MergeFrom(dir.File("other.sqlite")).status().code(),
            Status::Code::kInvalidArgument);
  EXPECT_FALSE(std::filesystem::exists(dir.File("missing.sqlite")));  // not created by merging
}

TEST(ExportTo, WritesAConsistentVerifiedCopy) {
  TempDir dir;
  auto main = MustOpen(dir.File("main.sqlite"));
  const std::vector<SetKey> keys = {Key1(64, 0), Key1(4096, 44), Key2(2048, 1, 179)};
  for (const SetKey& k : keys) ASSERT_TRUE(main->Put(MakeRecord(k, 5)).ok());
  const std::string out = dir.File("export.sqlite");
  ASSERT_TRUE(main->ExportTo(out).ok());
  EXPECT_FALSE(std::filesystem::exists(out + ".partial"));

  SetCache::Options ro;
  ro.read_only = true;
  auto copy = SetCache::Open(out, ro);
  ASSERT_TRUE(copy.ok()) << copy.status().ToString();
  EXPECT_EQ(*(*copy)->List(), *main->List());
  auto report = (*copy)->Verify();
  ASSERT_TRUE(report.ok());
  EXPECT_EQ(report->checked, 3);
  EXPECT_TRUE(report->corrupt.empty());
  for (const SetKey& k : keys) EXPECT_TRUE(BitEqual((*copy)->Get(k)->points, MakeRecord(k, 5).points));
  RawDb raw(out);
  EXPECT_EQ(raw.Text("PRAGMA integrity_check"), "ok");
}

TEST(ExportTo, RefusesAnExistingFile) {
  TempDir dir;
  auto main = MustOpen(dir.File("main.sqlite"));
  std::ofstream(dir.File("taken")) << "mine";
  EXPECT_EQ(main->ExportTo(dir.File("taken")).code(), Status::Code::kInvalidArgument);
  std::ifstream in(dir.File("taken"));
  std::string content;
  in >> content;
  EXPECT_EQ(content, "mine");
}

// Writers keep going during the export; the copy is one snapshot, so every
// set in it verifies.
TEST(ExportTo, SnapshotWhileWriting) {
  TempDir dir;
  auto main = MustOpen(dir.File("main.sqlite"));
  for (int i = 0; i < 10; ++i) ASSERT_TRUE(main->Put(MakeRecord(Key1(2048, i), 0)).ok());
  std::atomic<bool> stop{false};
  std::thread writer([&] {
    for (int g = 1; !stop; ++g) ASSERT_TRUE(main->Put(MakeRecord(Key1(2048, g % 40), g)).ok());
  });
  for (int e = 0; e < 3; ++e) {
    const std::string out = dir.File("e" + std::to_string(e) + ".sqlite");
    ASSERT_TRUE(main->ExportTo(out).ok());
    auto copy = SetCache::Open(out);
    ASSERT_TRUE(copy.ok());
    auto report = (*copy)->Verify();
    ASSERT_TRUE(report.ok());
    EXPECT_GE(report->checked, 10);
    EXPECT_TRUE(report->corrupt.empty());
  }
  stop = true;
  writer.join();
}

}  // namespace
}  // namespace alignset::storage

#include "storage/set_cache.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <limits>

#include "storage/profile.h"
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

void ExpectSameRecord(const SetRecord& got, const SetRecord& want) {
  EXPECT_EQ(got.key, want.key);
  EXPECT_TRUE(BitEqual(got.points, want.points));
  EXPECT_EQ(got.loss.total, want.loss.total);
  EXPECT_EQ(got.loss.spectrum, want.loss.spectrum);
  EXPECT_EQ(got.loss.sw, want.loss.sw);
  EXPECT_EQ(got.iterations, want.iterations);
  EXPECT_EQ(got.optimize_seconds, want.optimize_seconds);
  EXPECT_EQ(got.engine, want.engine);
  EXPECT_EQ(got.created_unix, want.created_unix);
  EXPECT_EQ(got.algorithm_version, want.algorithm_version);
}

TEST(SetCache, PutGetRoundTripIsBitExact) {
  TempDir dir;
  auto cache = MustOpen(dir.File("c.sqlite"));
  for (const SetKey& key : {Key1(16, 0), Key1(4096, 45), Key2(1000, 3, 177)}) {
    const SetRecord rec = MakeRecord(key, 3);
    ASSERT_TRUE(cache->Put(rec).ok());
    auto got = cache->Get(key);
    ASSERT_TRUE(got.ok()) << got.status().ToString();
    ExpectSameRecord(*got, rec);
  }
}

TEST(SetCache, SurvivesReopen) {
  TempDir dir;
  const SetRecord rec = MakeRecord(Key2(2048, 10, 100), 1);
  ASSERT_TRUE(MustOpen(dir.File("c.sqlite"))->Put(rec).ok());
  auto got = MustOpen(dir.File("c.sqlite"))->Get(rec.key);
  ASSERT_TRUE(got.ok());
  ExpectSameRecord(*got, rec);
}

TEST(SetCache, MissIsNotFound) {
  TempDir dir;
  auto cache = MustOpen(dir.File("c.sqlite"));
  ASSERT_TRUE(cache->Put(MakeRecord(Key1(64, 5))).ok());
  EXPECT_EQ(cache->Get(Key1(64, 6)).status().code(), Status::Code::kNotFound);
  EXPECT_EQ(cache->Get(Key1(128, 5)).status().code(), Status::Code::kNotFound);
  EXPECT_EQ(cache->Get(Key2(64, 5, 5)).status().code(), Status::Code::kNotFound);
  EXPECT_EQ(cache->Get(Key1(64, 5, "fedcba9876543210")).status().code(), Status::Code::kNotFound);
  EXPECT_TRUE(*cache->Contains(Key1(64, 5)));
  EXPECT_FALSE(*cache->Contains(Key1(64, 6)));
}

TEST(SetCache, PutReplacesTheRow) {
  TempDir dir;
  auto cache = MustOpen(dir.File("c.sqlite"));
  const SetKey key = Key1(256, 20);
  ASSERT_TRUE(cache->Put(MakeRecord(key, 1)).ok());
  const SetRecord second = MakeRecord(key, 2);
  ASSERT_TRUE(cache->Put(second).ok());
  auto got = cache->Get(key);
  ASSERT_TRUE(got.ok());
  ExpectSameRecord(*got, second);
  EXPECT_EQ(cache->Stats()->sets, 1);
}

// The point of the profile id: a set made with other parameters is a miss.
TEST(SetCache, ChangedParameterNeverReturnsAStaleSet) {
  TempDir dir;
  auto cache = MustOpen(dir.File("c.sqlite"));
  const FrequencyParams params = DefaultFrequencyParams(512);
  OptimizerOptions options;
  SetKey key = Key1(512, 30, ProfileId(params, options, 1));
  ASSERT_TRUE(cache->Put(MakeRecord(key)).ok());
  ASSERT_TRUE(cache->Get(key).ok());

  OptimizerOptions more = options;
  more.max_iterations += 1000;
  FrequencyParams wider = params;
  wider.width += 1.0;
  for (const std::string& profile :
       {ProfileId(params, more, 1), ProfileId(wider, options, 1), ProfileId(params, options, 2),
        ProfileId(params, options, 1, kAlgorithmVersion + 1)}) {
    key.profile = profile;
    EXPECT_EQ(cache->Get(key).status().code(), Status::Code::kNotFound) << profile;
  }
}

TEST(SetCache, FlippedBlobByteIsDataLossAndPutRepairsIt) {
  TempDir dir;
  const std::string path = dir.File("c.sqlite");
  auto cache = MustOpen(path);
  const SetKey bad = Key1(4096, 12), good = Key1(4096, 13);
  ASSERT_TRUE(cache->Put(MakeRecord(bad)).ok());
  ASSERT_TRUE(cache->Put(MakeRecord(good)).ok());
  {
    RawDb raw(path);
    // Byte 40000 lies in an overflow page of the 64 KiB blob; flipping its
    // lowest bit leaves every coordinate inside [0,1).
    ASSERT_TRUE(raw.FlipBlobByte(bad, 40000));
  }
  auto got = cache->Get(bad);
  EXPECT_EQ(got.status().code(), Status::Code::kDataLoss);
  EXPECT_NE(got.status().message().find("checksum"), std::string::npos) << got.status().message();
  EXPECT_TRUE(cache->Get(good).ok());

  auto report = cache->Verify();
  ASSERT_TRUE(report.ok());
  EXPECT_EQ(report->checked, 2);
  ASSERT_EQ(report->corrupt.size(), 1u);
  EXPECT_EQ(report->corrupt[0], bad);

  const SetRecord fresh = MakeRecord(bad, 9);
  ASSERT_TRUE(cache->Put(fresh).ok());
  auto repaired = cache->Get(bad);
  ASSERT_TRUE(repaired.ok());
  ExpectSameRecord(*repaired, fresh);
  EXPECT_TRUE(cache->Verify()->corrupt.empty());
}

TEST(SetCache, DamagedChecksumColumnOrTruncatedBlobIsDataLoss) {
  TempDir dir;
  const std::string path = dir.File("c.sqlite");
  auto cache = MustOpen(path);
  const SetKey a = Key1(64, 1), b = Key1(64, 2);
  ASSERT_TRUE(cache->Put(MakeRecord(a)).ok());
  ASSERT_TRUE(cache->Put(MakeRecord(b)).ok());
  {
    RawDb raw(path);
    ASSERT_TRUE(raw.Exec("UPDATE sets SET checksum = (checksum + 1) % 4294967296 WHERE phi1 = 1"));
    ASSERT_TRUE(raw.SetBlob(b, std::string(64 * 16 - 8, '\0')));
  }
  EXPECT_EQ(cache->Get(a).status().code(), Status::Code::kDataLoss);
  EXPECT_EQ(cache->Get(b).status().code(), Status::Code::kDataLoss);
  EXPECT_EQ(cache->Verify()->corrupt.size(), 2u);
}

TEST(SetCache, ListIsOrderedAndFiltersStatsCount) {
  TempDir dir;
  auto cache = MustOpen(dir.File("c.sqlite"));
  const std::vector<SetKey> keys = {Key2(64, 0, 90),  Key1(128, 45),         Key1(64, 30),
                                    Key1(64, 7),      Key2(64, 10, 20),      Key1(64, 7, "other"),
                                    Key1(128, 0, "other")};
  for (size_t i = 0; i < keys.size(); ++i) ASSERT_TRUE(cache->Put(MakeRecord(keys[i], int(i))).ok());

  auto all = cache->List();
  ASSERT_TRUE(all.ok());
  const std::vector<SetKey> want = {Key1(64, 7),   Key1(64, 7, "other"), Key1(64, 30),
                                    Key2(64, 0, 90), Key2(64, 10, 20),   Key1(128, 0, "other"),
                                    Key1(128, 45)};
  EXPECT_EQ(*all, want);
  EXPECT_EQ(cache->List(128u)->size(), 2u);
  EXPECT_EQ(cache->List(std::nullopt, std::string("other"))->size(), 2u);
  auto one = cache->List(64u, std::string("other"));
  ASSERT_EQ(one->size(), 1u);
  EXPECT_EQ((*one)[0], Key1(64, 7, "other"));
  EXPECT_TRUE(cache->List(32u)->empty());

  auto stats = cache->Stats();
  ASSERT_TRUE(stats.ok());
  EXPECT_EQ(stats->sets, 7);
  EXPECT_EQ(stats->one_direction_sets, 5);
  EXPECT_EQ(stats->two_direction_sets, 2);
  EXPECT_EQ(stats->bytes, (5 * 64 + 2 * 128) * 16);

  auto summaries = cache->ListSummaries(64u);
  ASSERT_TRUE(summaries.ok());
  ASSERT_EQ(summaries->size(), 5u);
  for (const SetSummary& s : *summaries) {
    auto rec = cache->Get(s.key);
    ASSERT_TRUE(rec.ok());
    EXPECT_EQ(s.bytes, 64 * 16);
    EXPECT_EQ(s.iterations, rec->iterations);
    EXPECT_EQ(s.loss.total, rec->loss.total);
    EXPECT_EQ(s.created_unix, rec->created_unix);
    EXPECT_EQ(s.engine, "direct");
    EXPECT_EQ(s.algorithm_version, kAlgorithmVersion);
  }
}

TEST(SetCache, EmptyCacheStatsAndVerify) {
  TempDir dir;
  auto cache = MustOpen(dir.File("c.sqlite"));
  EXPECT_EQ(cache->Stats()->sets, 0);
  EXPECT_EQ(cache->Stats()->bytes, 0);
  EXPECT_EQ(cache->Verify()->checked, 0);
  EXPECT_TRUE(cache->List()->empty());
}

TEST(SetCache, InvalidInputIsRejectedAndNothingIsWritten) {
  TempDir dir;
  auto cache = MustOpen(dir.File("c.sqlite"));
  std::vector<SetRecord> bad;
  bad.push_back(MakeRecord(Key1(64, 46)));       // phi outside [0,45]
  bad.push_back(MakeRecord(Key2(64, 100, 50)));  // phi1 > phi2
  bad.push_back(MakeRecord(Key2(64, 10, 180)));
  bad.push_back(MakeRecord(Key1(64, 3, "")));
  bad.push_back(MakeRecord(Key1(64, 3, "has space")));
  SetRecord r = MakeRecord(Key1(64, 3));
  r.key.dirs.count = 3;
  bad.push_back(r);
  r = MakeRecord(Key1(64, 3));
  r.key.dirs.phi2 = 4;  // one direction with a second angle
  bad.push_back(r);
  r = MakeRecord(Key1(64, 3));
  r.points.pop_back();
  bad.push_back(r);
  r = MakeRecord(Key1(64, 3));
  r.points[5].y = 1.0;
  bad.push_back(r);
  r = MakeRecord(Key1(64, 3));
  r.loss.sw = std::numeric_limits<double>::quiet_NaN();
  bad.push_back(r);
  r = MakeRecord(Key1(8, 3));
  bad.push_back(r);  // below kMinPoints
  for (const SetRecord& rec : bad) {
    EXPECT_EQ(cache->Put(rec).code(), Status::Code::kInvalidArgument) << KeyToString(rec.key);
  }
  EXPECT_EQ(cache->Stats()->sets, 0);
  EXPECT_EQ(cache->Get(Key1(64, 46)).status().code(), Status::Code::kInvalidArgument);
}

TEST(SetCache, ZeroCreatedTimeMeansNow) {
  TempDir dir;
  auto cache = MustOpen(dir.File("c.sqlite"));
  SetRecord r = MakeRecord(Key1(64, 3));
  r.created_unix = 0;
  const int64_t before = static_cast<int64_t>(std::time(nullptr));
  ASSERT_TRUE(cache->Put(r).ok());
  const int64_t stored = cache->Get(r.key)->created_unix;
  EXPECT_GE(stored, before);
  EXPECT_LE(stored, static_cast<int64_t>(std::time(nullptr)));
}

TEST(SetCache, ReadOnlyOpen) {
  TempDir dir;
  const std::string path = dir.File("c.sqlite");
  SetCache::Options ro;
  ro.read_only = true;
  EXPECT_EQ(SetCache::Open(path, ro).status().code(), Status::Code::kNotFound);
  const SetRecord rec = MakeRecord(Key1(64, 3));
  ASSERT_TRUE(MustOpen(path)->Put(rec).ok());
  auto cache = MustOpen(path, ro);
  ASSERT_TRUE(cache);
  ASSERT_TRUE(cache->Get(rec.key).ok());
  EXPECT_EQ(cache->Put(MakeRecord(Key1(64, 4))).code(), Status::Code::kInvalidArgument);
  EXPECT_EQ(cache->Stats()->sets, 1);
  EXPECT_EQ(cache->Verify()->checked, 1);
}

TEST(SetCache, OpenRejectsNonDatabasesAndMemory) {
  TempDir dir;
  const std::string junk = dir.File("junk.sqlite");
  std::ofstream(junk) << std::string(4096, 'x');
  EXPECT_EQ(SetCache::Open(junk).status().code(), Status::Code::kDataLoss);
  EXPECT_EQ(SetCache::Open(":memory:").status().code(), Status::Code::kInvalidArgument);
  EXPECT_EQ(SetCache::Open("").status().code(), Status::Code::kInvalidArgument);
  EXPECT_FALSE(SetCache::Open(dir.File("no/such/dir/c.sqlite")).ok());
}

TEST(SetCache, JournalModeIsWal) {
  TempDir dir;
  const std::string path = dir.File("c.sqlite");
  auto cache = MustOpen(path);
  ASSERT_TRUE(cache->Put(MakeRecord(Key1(64, 3))).ok());
  RawDb raw(path);
  EXPECT_EQ(raw.Text("PRAGMA journal_mode"), "wal");  // persistent in the file
}

TEST(SetCache, KeyToStringNamesEveryPart) {
  EXPECT_EQ(KeyToString(Key1(4096, 30, "abc")), "n=4096 dirs=1:30 profile=abc");
  EXPECT_EQ(KeyToString(Key2(64, 3, 177, "p")), "n=64 dirs=2:3,177 profile=p");
}

}  // namespace
}  // namespace alignset::storage

#include "storage/cache_diff.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "tests/storage/test_util.h"

namespace alignset::storage {
namespace {

using testing::Key1;
using testing::Key2;
using testing::MakeRecord;
using testing::MustOpen;
using testing::RawDb;
using testing::TempDir;
using testing::WithRealization;

bool Holds(const std::vector<SetKey>& keys, const SetKey& k) {
  return std::ranges::find(keys, k) != keys.end();
}

TEST(DiffCaches, SameSetsFilledAtOtherTimesAgree) {
  TempDir dir;
  auto a = MustOpen(dir.File("a.sqlite"));
  auto b = MustOpen(dir.File("b.sqlite"));
  const std::vector<SetKey> keys = {Key1(64, 0), Key1(64, 45), Key2(128, 3, 91),
                                    WithRealization(Key1(64, 0), 2)};
  for (const SetKey& k : keys) {
    ASSERT_TRUE(a->Put(MakeRecord(k, 1)).ok());
    // The same points, other metadata: another server's fill of the key.
    SetRecord r = MakeRecord(k, 1);
    r.iterations = 77;
    r.optimize_seconds = 9.5;
    r.created_unix += 3600;
    r.engine = "fast";
    ASSERT_TRUE(b->Put(r).ok());
  }
  auto d = DiffCaches(*a, *b);
  ASSERT_TRUE(d.ok()) << d.status().ToString();
  EXPECT_EQ(d->same, 4);
  EXPECT_TRUE(d->SharedAgree());
  EXPECT_TRUE(d->only_first.empty());
  EXPECT_TRUE(d->only_second.empty());
}

TEST(DiffCaches, FindsOnePointOneUlpApartAndKeysOnlyOneFileHolds) {
  TempDir dir;
  auto a = MustOpen(dir.File("a.sqlite"));
  auto b = MustOpen(dir.File("b.sqlite"));
  const SetKey shared = Key1(256, 30), moved = Key2(64, 10, 100);
  // Keys that differ from a shared one in one field only: the profile, the
  // realization, the direction count.
  const SetKey only_a = Key1(256, 30, "fedcba9876543210");
  const SetKey only_b = WithRealization(Key1(256, 30), 1);
  const SetKey only_b2 = Key2(256, 30, 30);
  // The same N and directions under two profiles, one in each file.
  const SetKey profile_a = Key1(512, 9, "aaaaaaaaaaaaaaaa"), profile_b = Key1(512, 9, "bbbbbbbbbbbbbbbb");
  for (const SetKey& k : {shared, moved, only_a, profile_a}) ASSERT_TRUE(a->Put(MakeRecord(k, 1)).ok());
  for (const SetKey& k : {shared, only_b, only_b2, profile_b}) ASSERT_TRUE(b->Put(MakeRecord(k, 1)).ok());
  SetRecord r = MakeRecord(moved, 1);
  r.points[7].y = std::nextafter(r.points[7].y, 2.0);
  ASSERT_TRUE(b->Put(r).ok());

  auto d = DiffCaches(*a, *b);
  ASSERT_TRUE(d.ok()) << d.status().ToString();
  EXPECT_EQ(d->same, 1);
  ASSERT_EQ(d->differing.size(), 1u);
  EXPECT_EQ(d->differing[0].key, moved);
  EXPECT_EQ(d->differing[0].points, 1);
  EXPECT_FALSE(d->SharedAgree());
  EXPECT_EQ(d->only_first.size(), 2u);
  EXPECT_TRUE(Holds(d->only_first, only_a));
  EXPECT_TRUE(Holds(d->only_first, profile_a));
  EXPECT_EQ(d->only_second.size(), 3u);
  EXPECT_TRUE(Holds(d->only_second, only_b));
  EXPECT_TRUE(Holds(d->only_second, only_b2));
  EXPECT_TRUE(Holds(d->only_second, profile_b));

  // Restricted to one N, the other N's difference is out of view.
  auto d256 = DiffCaches(*a, *b, 256u);
  ASSERT_TRUE(d256.ok());
  EXPECT_EQ(d256->same, 1);
  EXPECT_TRUE(d256->SharedAgree());
  EXPECT_EQ(d256->only_first.size(), 1u);
}

TEST(DiffCaches, ADamagedRowIsNamedWithItsFileNotCountedTheSame) {
  TempDir dir;
  const SetKey k1 = Key1(64, 5), k2 = Key1(64, 6), k3 = Key1(64, 7);
  {
    auto a = MustOpen(dir.File("a.sqlite"));
    auto b = MustOpen(dir.File("b.sqlite"));
    for (const SetKey& k : {k1, k2, k3}) {
      ASSERT_TRUE(a->Put(MakeRecord(k, 1)).ok());
      ASSERT_TRUE(b->Put(MakeRecord(k, 1)).ok());
    }
  }
  {
    RawDb raw_a(dir.File("a.sqlite"));
    RawDb raw_b(dir.File("b.sqlite"));
    ASSERT_TRUE(raw_b.FlipBlobByte(k2, 40));
    ASSERT_TRUE(raw_a.FlipBlobByte(k3, 40));
    ASSERT_TRUE(raw_b.FlipBlobByte(k3, 41));
  }
  auto a = MustOpen(dir.File("a.sqlite"));
  auto b = MustOpen(dir.File("b.sqlite"));
  auto d = DiffCaches(*a, *b);
  ASSERT_TRUE(d.ok()) << d.status().ToString();
  EXPECT_EQ(d->same, 1);
  EXPECT_TRUE(d->differing.empty());
  ASSERT_EQ(d->damaged.size(), 2u);
  EXPECT_EQ(d->damaged[0].key, k2);
  EXPECT_FALSE(d->damaged[0].in_first);
  EXPECT_TRUE(d->damaged[0].in_second);
  EXPECT_EQ(d->damaged[1].key, k3);
  EXPECT_TRUE(d->damaged[1].in_first);
  EXPECT_TRUE(d->damaged[1].in_second);
  EXPECT_FALSE(d->SharedAgree());
}

}  // namespace
}  // namespace alignset::storage

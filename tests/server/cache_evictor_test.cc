// CacheEvictor (--max-cache-bytes) on a real SQLite file: least recently
// served first, never a pinned set (one a call waits for), and the file
// returns its free pages.
#include "server/cache_evictor.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <set>

#include "server/set_lru.h"
#include "tests/server/scheduler_fixture.h"
#include "tests/storage/test_util.h"

namespace alignset::server {
namespace {

using storage::testing::Key1;
using storage::testing::MakeRecord;

class CacheEvictorTest : public ::testing::Test {
 protected:
  void SetUp() override {
    cache_ = storage::testing::MustOpen(dir_.File("cache.sqlite"));
    ASSERT_NE(cache_, nullptr);
  }
  // Stores sets at phi = 0 .. count-1 (N = 1024), in that order, in a file
  // already switched to incremental vacuum (Start's switch would otherwise
  // change the pages in use).
  void Fill(int count) {
    ASSERT_TRUE(cache_->EnableIncrementalVacuum().ok());
    for (int phi = 0; phi < count; ++phi) ASSERT_TRUE(cache_->Put(MakeRecord(Key1(1024, phi))).ok());
  }
  bool Stored(int phi) { return cache_->Contains(Key1(1024, phi)).value(); }

  storage::testing::TempDir dir_;
  std::unique_ptr<storage::SetCache> cache_;
  Metrics metrics_;
};

TEST_F(CacheEvictorTest, EvictsTheLeastRecentlyServedButNeverAPinnedSet) {
  Fill(6);
  const int64_t used = cache_->Space()->used_bytes();
  std::set<std::string> pinned = {KeyString(Key1(1024, 0))};
  std::vector<std::string> evicted;
  CacheEvictor::Options o;
  o.max_bytes = used;  // full: the next set needs room
  o.pinned = [&](const std::string& name) { return pinned.count(name) != 0; };
  o.evicted = [&](const std::string& name) { evicted.push_back(name); };
  CacheEvictor ev(cache_.get(), &metrics_, o);
  ASSERT_TRUE(ev.Start().ok());
  // Served since: 1 and 3 (so the order is now 0, 2, 4, 5, 1, 3).
  ev.Touch(KeyString(Key1(1024, 1)), Key1(1024, 1));
  ev.Touch(KeyString(Key1(1024, 3)), Key1(1024, 3));
  const storage::SetKey incoming = Key1(1024, 40);
  ASSERT_TRUE(ev.MakeRoom(incoming, ev.EstimateBytes(1024)).ok());
  // 0 is the oldest but pinned; 2 goes (and 4 if one was not enough).
  EXPECT_TRUE(Stored(0));
  EXPECT_FALSE(Stored(2));
  EXPECT_TRUE(Stored(1));
  EXPECT_TRUE(Stored(3));
  ASSERT_FALSE(evicted.empty());
  EXPECT_EQ(evicted[0], KeyString(Key1(1024, 2)));
  EXPECT_EQ(metrics_.cache_evictions.load(), evicted.size());
  EXPECT_LE(cache_->Space()->used_bytes() + ev.EstimateBytes(1024), o.max_bytes);
  ASSERT_TRUE(cache_->Put(MakeRecord(incoming)).ok());
  EXPECT_LE(cache_->Space()->used_bytes(), o.max_bytes);
}

TEST_F(CacheEvictorTest, WhenEverySetIsPinnedNothingIsEvictedAndTheNewSetIsRefused) {
  Fill(3);
  CacheEvictor::Options o;
  o.max_bytes = cache_->Space()->used_bytes();
  o.pinned = [](const std::string&) { return true; };
  CacheEvictor ev(cache_.get(), &metrics_, o);
  ASSERT_TRUE(ev.Start().ok());
  const Status s = ev.MakeRoom(Key1(1024, 30), ev.EstimateBytes(1024));
  EXPECT_EQ(s.code(), Status::Code::kResourceExhausted) << s.message();
  for (int phi = 0; phi < 3; ++phi) EXPECT_TRUE(Stored(phi));  // nothing already stored is lost
  EXPECT_EQ(metrics_.cache_evictions.load(), 0u);
}

TEST_F(CacheEvictorTest, TheBackgroundVacuumShrinksTheFile) {
  Fill(12);
  const int64_t full = cache_->Space()->file_bytes();
  CacheEvictor::Options o;
  o.max_bytes = full / 2;
  {
    CacheEvictor ev(cache_.get(), &metrics_, o);
    ASSERT_TRUE(ev.Start().ok());  // over the bound at start: shrinks at once
    for (int i = 0; i < 100 && metrics_.cache_vacuums.load() == 0; ++i) {
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
  }
  EXPECT_GT(metrics_.cache_evictions.load(), 0u);
  EXPECT_GT(metrics_.cache_vacuums.load(), 0u);
  const storage::FileSpace after = cache_->Space().value();
  EXPECT_EQ(after.freelist_count, 0);
  EXPECT_LE(after.file_bytes(), o.max_bytes);
}

// The scheduler's pin: a key is in flight (a call waits for it) from the
// moment its job is queued until the job ends.
class SchedulerPinTest : public testing::SchedulerFixture {};

TEST_F(SchedulerPinTest, AKeyIsPinnedWhileACallWaitsForIt) {
  gate_->Close();
  Scheduler::Options o;
  o.workers = 1;
  o.producer.optimizer.max_iterations = 5;
  o.producer.max_cache_bytes = 1 << 20;
  StartWith(o);
  const storage::SetKey running = Key(64, 3), queued = Key(64, 4);
  auto t1 = MustAcquire(running, Priority::kInteractive);
  auto t2 = MustAcquire(queued, Priority::kInteractive);
  EXPECT_TRUE(scheduler_->InFlight(KeyString(running)));
  EXPECT_TRUE(scheduler_->InFlight(KeyString(queued)));
  EXPECT_FALSE(scheduler_->InFlight(KeyString(Key(64, 5))));
  gate_->Open();
  WaitDone(*t1, 600);
  WaitDone(*t2, 600);
  EXPECT_FALSE(scheduler_->InFlight(KeyString(running)));
  EXPECT_TRUE(cache_->Contains(running).value());
  EXPECT_TRUE(cache_->Contains(queued).value());
}

}  // namespace
}  // namespace alignset::server

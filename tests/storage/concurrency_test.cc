#include <gtest/gtest.h>

#include <atomic>
#include <thread>
#include <vector>

#include "storage/set_cache.h"
#include "tests/storage/test_util.h"

namespace alignset::storage {
namespace {

using testing::BitEqual;
using testing::Key1;
using testing::Key2;
using testing::MakeRecord;
using testing::TempDir;

constexpr int kThreads = 4;
constexpr int kPerThread = 20;

SetKey ThreadKey(int t, int i) { return Key2(256, t, 100 + i); }

// The server's pattern: one SetCache shared by request and worker threads.
TEST(Concurrency, ThreadsShareOneCache) {
  TempDir dir;
  auto opened = SetCache::Open(dir.File("c.sqlite"));
  ASSERT_TRUE(opened.ok());
  SetCache& cache = **opened;
  std::atomic<int> failures{0};
  std::vector<std::thread> threads;
  for (int t = 0; t < kThreads; ++t) {
    threads.emplace_back([&, t] {
      for (int i = 0; i < kPerThread; ++i) {
        const SetRecord rec = MakeRecord(ThreadKey(t, i), t);
        if (!cache.Put(rec).ok()) ++failures;
        auto got = cache.Get(rec.key);
        if (!got.ok() || !BitEqual(got->points, rec.points)) ++failures;
        // Reads of other threads' keys race with their writes: a hit must
        // be whole, a miss is fine.
        auto other = cache.Get(ThreadKey((t + 1) % kThreads, i));
        if (!other.ok() && other.status().code() != Status::Code::kNotFound) ++failures;
        if (!cache.List(256u).ok() || !cache.Stats().ok()) ++failures;
      }
    });
  }
  for (auto& th : threads) th.join();
  EXPECT_EQ(failures.load(), 0);
  EXPECT_EQ(cache.Stats()->sets, kThreads * kPerThread);
  auto report = cache.Verify();
  ASSERT_TRUE(report.ok());
  EXPECT_EQ(report->checked, kThreads * kPerThread);
  EXPECT_TRUE(report->corrupt.empty());
}

// Several connections (as several processes would have) on one new file:
// they race to switch it to WAL and to migrate it, then write concurrently;
// the busy timeout makes them wait instead of failing.
TEST(Concurrency, SeparateConnectionsOnOneFile) {
  TempDir dir;
  const std::string path = dir.File("c.sqlite");
  std::atomic<int> failures{0};
  std::vector<std::thread> threads;
  for (int t = 0; t < kThreads; ++t) {
    threads.emplace_back([&, t] {
      auto cache = SetCache::Open(path);
      if (!cache.ok()) {
        ADD_FAILURE() << cache.status().ToString();
        ++failures;
        return;
      }
      for (int i = 0; i < kPerThread / 2; ++i) {
        Status s = (*cache)->Put(MakeRecord(ThreadKey(t, i), t));
        if (!s.ok()) {
          ADD_FAILURE() << s.ToString();
          ++failures;
        }
      }
    });
  }
  for (auto& th : threads) th.join();
  EXPECT_EQ(failures.load(), 0);
  auto cache = SetCache::Open(path);
  ASSERT_TRUE(cache.ok());
  EXPECT_EQ((*cache)->Stats()->sets, kThreads * (kPerThread / 2));
  EXPECT_TRUE((*cache)->Verify()->corrupt.empty());
}

}  // namespace
}  // namespace alignset::storage

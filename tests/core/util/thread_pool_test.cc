#include "core/util/thread_pool.h"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <thread>
#include <vector>

namespace alignset {
namespace {

// Every index of every loop is visited exactly once, by a worker index in
// range, whatever the loop length relative to the pool size.
TEST(ThreadPoolTest, EachIndexExactlyOnce) {
  for (int threads : {1, 2, 3, 5}) {
    ThreadPool pool(threads);
    EXPECT_EQ(pool.size(), threads);
    for (size_t n : {0u, 1u, 2u, 3u, 7u, 64u, 1001u}) {
      std::vector<std::atomic<int>> hits(n);
      std::atomic<bool> bad_worker{false};
      pool.ParallelFor(n, [&](size_t b, size_t e, int w) {
        if (w < 0 || w >= threads) bad_worker = true;
        for (size_t i = b; i < e; ++i) hits[i].fetch_add(1);
      });
      EXPECT_FALSE(bad_worker);
      for (size_t i = 0; i < n; ++i) ASSERT_EQ(hits[i].load(), 1) << "n=" << n << " i=" << i;
    }
  }
}

// Back-to-back loops (the spinning hand-over) and loops after the workers
// have gone to sleep (the blocking hand-over) both complete and see the
// writes of the loop before them.
TEST(ThreadPoolTest, ManyLoopsBackToBackAndAfterSleeping) {
  ThreadPool pool(3);
  std::vector<long> data(300, 0);
  for (int round = 0; round < 2000; ++round) {
    pool.ParallelFor(data.size(), [&](size_t b, size_t e, int) {
      for (size_t i = b; i < e; ++i) data[i] += 1;
    });
    if (round % 500 == 0) {
      // Longer than the spin window, so the next loop must wake sleepers.
      std::this_thread::sleep_for(std::chrono::microseconds(5 * ThreadPool::kSpinMicroseconds));
    }
  }
  for (long v : data) ASSERT_EQ(v, 2000);
}

TEST(ThreadPoolTest, DestroysCleanlyWhileWorkersSleepOrSpin) {
  for (int i = 0; i < 20; ++i) {
    ThreadPool pool(4);
    std::atomic<int> sum{0};
    pool.ParallelFor(8, [&](size_t b, size_t e, int) { sum += static_cast<int>(e - b); });
    EXPECT_EQ(sum.load(), 8);
    if (i % 2) std::this_thread::sleep_for(std::chrono::microseconds(3 * ThreadPool::kSpinMicroseconds));
  }
}

}  // namespace
}  // namespace alignset

#include "server/process_memory.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <barrier>
#include <cstdlib>
#include <thread>
#include <vector>

namespace alignset::server {
namespace {

#if defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(thread_sanitizer) || __has_feature(memory_sanitizer)
#define ALIGNSET_SANITIZER_MALLOC 1
#endif
#endif
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
#define ALIGNSET_SANITIZER_MALLOC 1
#endif

// Threads that each allocate while all of them are alive: glibc gives every
// new thread an arena of its own until the cap is reached.
void AllocateFromThreads(int threads) {
  std::barrier all_alive(threads);
  std::vector<std::thread> pool;
  for (int i = 0; i < threads; ++i) {
    pool.emplace_back([&all_alive] {
      std::vector<void*> blocks;
      for (int j = 0; j < 64; ++j) blocks.push_back(std::malloc(1024 + 64 * j));
      all_alive.arrive_and_wait();
      for (void* b : blocks) std::free(b);
    });
  }
  for (auto& t : pool) t.join();
}

// Without the cap the 12 threads make 12 arenas (a server on two cores with
// MALLOC_ARENA_MAX=64 made 13 for 14 threads, with the cap 2; counted in
// /proc/PID/maps). glibc reads the cap once, when the first thread needs an
// arena, so there is no uncapped control in the same process. CTest runs
// each test in a process of its own, so `before` is the main arena alone
// there; run together with other threaded tests the bound is whatever they
// made before the cap.
TEST(ProcessMemory, TheArenaCapHoldsUnderManyThreads) {
#if defined(ALIGNSET_SANITIZER_MALLOC)
  GTEST_SKIP() << "a sanitizer's malloc replaces glibc's (its mallopt does nothing)";
#endif
  if (MallocArenas() < 0) GTEST_SKIP() << "not glibc's malloc";
  if (std::getenv("MALLOC_ARENA_MAX") || std::getenv("GLIBC_TUNABLES")) {
    EXPECT_EQ(LimitAllocatorKeeping(2), "") << "the operator's setting is left alone";
    return;
  }
  const int before = MallocArenas();
  EXPECT_EQ(LimitAllocatorKeeping(2), "glibc malloc: at most 2 arenas");
  AllocateFromThreads(12);
  EXPECT_LE(MallocArenas(), std::max(before, 2));
}

TEST(ProcessMemory, ResidentFiguresAddUp) {
  const ProcessMemory m = ReadProcessMemory();
  EXPECT_GT(m.resident_bytes, 0);
  EXPECT_GT(m.resident_anonymous_bytes, 0);
  EXPECT_GE(m.resident_bytes, m.resident_anonymous_bytes + m.resident_file_bytes);
  EXPECT_FALSE(m.allocator.empty());
}

}  // namespace
}  // namespace alignset::server

// A writer process killed with SIGKILL at random moments must never leave a
// corrupt file or a half-written set behind.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <set>
#include <cstdio>
#include <thread>

#include "core/util/hash.h"
#include "storage/set_cache.h"
#include "tests/storage/test_util.h"

namespace alignset::storage {
namespace {

using testing::BitEqual;
using testing::Key1;
using testing::Key2;
using testing::MakeRecord;
using testing::RawDb;
using testing::TempDir;

// Sizes from one page to 1 MiB (many overflow pages, and WAL checkpoints
// every few writes), so kills land inside large multi-page writes too.
const std::vector<SetKey>& Keys() {
  static const std::vector<SetKey> keys = {Key1(16, 0),      Key1(1024, 5),   Key2(4096, 10, 20),
                                           Key1(65536, 30),  Key2(16384, 0, 179), Key1(300, 45)};
  return keys;
}

constexpr int kGenerations = 8;

// The child: replaces sets forever, cycling through generations 1..8 of
// every key, until killed. The records are made before it signals `ready_fd`,
// so the loop spends its time writing and a kill most likely lands inside
// SQLite.
[[noreturn]] void WriterChild(const std::string& path, int ready_fd, uint64_t seed) {
  auto cache = SetCache::Open(path);
  if (!cache.ok()) _exit(3);
  std::vector<SetRecord> records;
  for (const SetKey& key : Keys()) {
    for (int gen = 1; gen <= kGenerations; ++gen) records.push_back(MakeRecord(key, gen));
  }
  const char byte = 'r';
  if (write(ready_fd, &byte, 1) != 1) _exit(4);
  Pcg32 rng(seed);
  for (;;) {
    const SetRecord& rec = records[rng.Uniform(static_cast<uint32_t>(records.size()))];
    if (!(*cache)->Put(rec).ok()) _exit(5);
  }
}

// How long one Put of the writer's takes on this machine and build: the
// kills' window is in these units, so a slow build (a sanitizer's) still
// lets the writers commit several generations between kills.
std::chrono::microseconds MeanPutTime(const std::string& path) {
  auto cache = SetCache::Open(path);
  EXPECT_TRUE(cache.ok()) << cache.status().ToString();
  if (!cache.ok()) return std::chrono::microseconds(1000);
  std::vector<SetRecord> records;
  for (const SetKey& key : Keys()) records.push_back(MakeRecord(key, 1));
  const auto start = std::chrono::steady_clock::now();
  constexpr int kPasses = 2;
  for (int pass = 0; pass < kPasses; ++pass) {
    for (const SetRecord& rec : records) EXPECT_TRUE((*cache)->Put(rec).ok());
  }
  const auto elapsed = std::chrono::steady_clock::now() - start;
  return std::chrono::duration_cast<std::chrono::microseconds>(elapsed) / (kPasses * records.size());
}

TEST(CrashSafety, SigkillDuringWritesNeverCorrupts) {
  TempDir dir;
  const std::string path = dir.File("c.sqlite");
  // Kills land from a quarter of a write to about twelve writes after the
  // writer starts (with at least the 1 ms this test has always waited).
  const std::chrono::microseconds put = MeanPutTime(path);
  const auto earliest = std::max<std::chrono::microseconds>(std::chrono::microseconds(1000), put / 4);
  const uint32_t span_us = static_cast<uint32_t>(std::max<int64_t>(30000, 12 * put.count()));
  std::printf("one Put: %lld us; kills %lld us + up to %u us after the writer starts\n",
              static_cast<long long>(put.count()), static_cast<long long>(earliest.count()), span_us);
  Pcg32 rng(2024);
  constexpr int kRounds = 24;
  std::set<std::pair<std::string, int>> seen;  // (key, generation) found stored
  for (int round = 0; round < kRounds; ++round) {
    int fds[2];
    ASSERT_EQ(pipe(fds), 0);
    const pid_t pid = fork();
    ASSERT_GE(pid, 0);
    if (pid == 0) {
      close(fds[0]);
      WriterChild(path, fds[1], 1000 + round);
    }
    close(fds[1]);
    char byte = 0;
    ASSERT_EQ(read(fds[0], &byte, 1), 1) << "writer did not start";
    close(fds[0]);
    std::this_thread::sleep_for(earliest + std::chrono::microseconds(rng.Uniform(span_us)));
    ASSERT_EQ(kill(pid, SIGKILL), 0);
    int status = 0;
    ASSERT_EQ(waitpid(pid, &status, 0), pid);
    ASSERT_TRUE(WIFSIGNALED(status)) << "writer exited on its own with " << WEXITSTATUS(status);

    {
      RawDb raw(path);
      ASSERT_EQ(raw.Text("PRAGMA integrity_check"), "ok") << "round " << round;
    }
    auto cache = SetCache::Open(path);
    ASSERT_TRUE(cache.ok()) << cache.status().ToString();
    auto report = (*cache)->Verify();
    ASSERT_TRUE(report.ok()) << report.status().ToString();
    EXPECT_TRUE(report->corrupt.empty()) << "round " << round;
    // Every stored set is exactly the one its generation (kept in the
    // iterations column) describes: blob and metadata of one write.
    auto keys = (*cache)->List();
    ASSERT_TRUE(keys.ok());
    for (const SetKey& k : *keys) {
      auto rec = (*cache)->Get(k);
      ASSERT_TRUE(rec.ok()) << rec.status().ToString();
      const SetRecord want = MakeRecord(k, rec->iterations);
      EXPECT_TRUE(BitEqual(rec->points, want.points)) << KeyToString(k);
      EXPECT_EQ(rec->loss.total, want.loss.total);
      EXPECT_EQ(rec->created_unix, want.created_unix);
      EXPECT_GE(rec->iterations, 1);
      EXPECT_LE(rec->iterations, kGenerations);
      seen.insert({KeyToString(k), rec->iterations});
    }
  }
  std::printf("%d kills, %zu distinct (set, generation) pairs seen stored\n", kRounds, seen.size());
  // The writers made progress between kills: far more than one
  // generation per key was seen committed.
  EXPECT_GT(seen.size(), 2 * Keys().size());
}

}  // namespace
}  // namespace alignset::storage

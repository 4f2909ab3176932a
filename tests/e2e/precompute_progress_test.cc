// A precompute stream keeps moving while a long item runs: updates at
// least twice a second (the server's heartbeat), each with the running
// items' fraction of their iterations, so a bar advances within the item
// instead of standing still for the seconds to minutes it takes. A real
// server on loopback.
#include <gtest/gtest.h>

#include <alignset/client.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <vector>

#include "tests/e2e/server_process.h"

namespace alignset::e2e {
namespace {

TEST(PrecomputeProgress, ALongItemMovesTheBarAndUpdatesArriveTwiceASecond) {
  TempDir dir;
  // One item of a few seconds on this machine (N = 4096, 3000 iterations).
  ServerProcess server(dir.path(), {"--max-iterations", "3000", "--workers", "1"});
  ASSERT_EQ(server.error(), "");
  auto client = ConnectTo(server);
  ASSERT_NE(client, nullptr);

  struct Seen {
    std::chrono::steady_clock::time_point at;
    double fraction;
    uint64_t done;
  };
  std::vector<Seen> seen;
  PrecomputeSpec spec;
  spec.n = {4096};
  spec.space = 0;
  spec.keys = {{30}};
  auto last = client->Precompute(spec, [&](const PrecomputeUpdate& u) {
    seen.push_back({std::chrono::steady_clock::now(), u.running_fraction, u.done});
  });
  ASSERT_TRUE(last.ok()) << last.status().message();
  EXPECT_EQ(last->done, 1u);
  EXPECT_EQ(last->running_fraction, 0.0);  // nothing runs after the end

  // The updates while the item ran (before the one that counts it done).
  std::vector<Seen> running;
  for (const Seen& s : seen) {
    if (s.done == 0) running.push_back(s);
  }
  ASSERT_GE(running.size(), 4u) << "the stream stood still while the item ran";
  double max_gap = 0.0, max_fraction = 0.0;
  std::vector<double> gaps;
  for (size_t i = 1; i < running.size(); ++i) {
    const double gap = std::chrono::duration<double>(running[i].at - running[i - 1].at).count();
    gaps.push_back(gap);
    max_gap = std::max(max_gap, gap);
    EXPECT_GE(running[i].fraction, running[i - 1].fraction) << "the bar went back at update " << i;
    max_fraction = std::max(max_fraction, running[i].fraction);
  }
  std::sort(gaps.begin(), gaps.end());
  const double median_gap = gaps[gaps.size() / 2];
  std::printf("%zu updates while the item ran; gaps median %.3f s, max %.3f s; fraction reached %.3f\n",
              running.size(), median_gap, max_gap, max_fraction);
  EXPECT_LE(median_gap, 0.75);
  // Generous against a loaded machine: the heartbeat is 0.5 s.
  EXPECT_LE(max_gap, 2.0);
  EXPECT_GT(max_fraction, 0.5);
  EXPECT_LE(max_fraction, 1.0);
}

}  // namespace
}  // namespace alignset::e2e

#include "server/watch_pacer.h"

#include <gtest/gtest.h>

namespace alignset::server {
namespace {

using namespace std::chrono_literals;
using Send = WatchPacer::Send;

JobView Running(uint64_t version) {
  JobView v;
  v.state = JobView::State::kRunning;
  v.version = version;
  return v;
}

TEST(WatchPacerTest, ProgressInsideTheWindowIsDelayedNotDropped) {
  WatchPacer pacer(100ms, 1000ms);
  const auto t0 = WatchPacer::Clock::now();
  EXPECT_EQ(pacer.Next(Running(1), t0), Send::kProgress);  // first: at once
  // News 30 ms later: held back, and the pacer asks to be called when the
  // window closes.
  EXPECT_EQ(pacer.Next(Running(2), t0 + 30ms), Send::kNothing);
  EXPECT_EQ(pacer.Wait(t0 + 30ms), 70ms);
  // No further callback arrives (the next one is 400 ms away at large N):
  // the held-back progress still goes out when the window closes.
  EXPECT_EQ(pacer.Next(Running(2), t0 + 100ms), Send::kProgress);
}

TEST(WatchPacerTest, HeartbeatEverySecondWithoutNews) {
  WatchPacer pacer(100ms, 1000ms);
  const auto t0 = WatchPacer::Clock::now();
  EXPECT_EQ(pacer.Next(Running(5), t0), Send::kProgress);
  EXPECT_EQ(pacer.Next(Running(5), t0 + 500ms), Send::kNothing);
  EXPECT_EQ(pacer.Wait(t0 + 500ms), 500ms);
  EXPECT_EQ(pacer.Next(Running(5), t0 + 1000ms), Send::kProgress);
}

TEST(WatchPacerTest, QueuePositionChangesGoOutAtOnce) {
  WatchPacer pacer(100ms, 1000ms);
  const auto t0 = WatchPacer::Clock::now();
  JobView q;
  q.state = JobView::State::kQueued;
  q.queue_position = 3;
  EXPECT_EQ(pacer.Next(q, t0), Send::kQueued);
  EXPECT_EQ(pacer.Next(q, t0 + 10ms), Send::kNothing);
  q.queue_position = 2;
  EXPECT_EQ(pacer.Next(q, t0 + 20ms), Send::kQueued);
  EXPECT_EQ(pacer.Next(Running(9), t0 + 30ms), Send::kProgress);  // state change
  JobView done;
  EXPECT_EQ(pacer.Next(done, t0 + 40ms), Send::kNothing);
}

}  // namespace
}  // namespace alignset::server

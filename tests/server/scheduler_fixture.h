#pragma once

// The fixture the scheduler's unit tests share: a real SQLite cache in a
// fresh directory and a scheduler whose engines wait at a gate the test holds.
#include <gtest/gtest.h>

#include <chrono>
#include <memory>
#include <string>
#include <utility>

#include "server/scheduler.h"
#include "tests/server/gated_engine.h"
#include "tests/storage/test_util.h"

namespace alignset::server::testing {

class SchedulerFixture : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_FALSE(dir_.path().empty());
    cache_ = storage::testing::MustOpen(dir_.File("cache.sqlite"));
    ASSERT_NE(cache_, nullptr);
  }
  // The scheduler goes before the cache it writes to, the cache before its directory.
  void TearDown() override {
    scheduler_.reset();
    cache_.reset();
  }

  // Starts the scheduler on `o`, its engines gated by gate_.
  void StartWith(Scheduler::Options o) {
    o.engine_factory = [g = gate_]() -> StatusOr<std::unique_ptr<SpectralEngine>> {
      return std::unique_ptr<SpectralEngine>(std::make_unique<GatedEngine>(g));
    };
    auto s = Scheduler::Create(o, cache_.get(), &metrics_);
    ASSERT_TRUE(s.ok()) << s.status().message();
    scheduler_ = std::move(s).value();
  }
  storage::SetKey Key(uint32_t n, int phi) { return scheduler_->producer().KeyFor(n, {1, phi, phi}); }
  std::unique_ptr<Ticket> MustAcquire(const storage::SetKey& key, Priority p,
                                      const std::string& client = "") {
    auto t = scheduler_->Acquire(key, p, client);
    EXPECT_TRUE(t.ok()) << t.status().message();
    return t.ok() ? std::move(t).value() : nullptr;
  }
  // Waits up to polls × 100 ms for the ticket's job to end.
  static void WaitDone(const Ticket& t, int polls) {
    using namespace std::chrono_literals;
    for (int i = 0; i < polls && !t.Wait(100ms); ++i) {
    }
    ASSERT_TRUE(t.Done());
  }
  // Waits, on the job's own change events, until it runs (or 10 s pass).
  static void WaitRunning(const Ticket& t) {
    using namespace std::chrono_literals;
    const auto end = std::chrono::steady_clock::now() + 10s;
    JobView v = t.View();
    while (v.state != JobView::State::kRunning && std::chrono::steady_clock::now() < end) {
      v = t.WaitForChange(v.version, 100ms);
    }
    ASSERT_EQ(v.state, JobView::State::kRunning);
  }
  // Waits, on the job's progress events, until it has run `iterations`
  // (or 10 s pass); returns what it saw last.
  static JobView WaitIterations(const Ticket& t, int iterations) {
    using namespace std::chrono_literals;
    const auto end = std::chrono::steady_clock::now() + 10s;
    JobView v = t.View();
    while (v.progress.iteration < iterations && v.state != JobView::State::kDone &&
           std::chrono::steady_clock::now() < end) {
      v = t.WaitForChange(v.version, 100ms);
    }
    return v;
  }
  // Waits on the scheduler's count changes until nothing runs or waits.
  bool WaitIdle(std::chrono::milliseconds timeout = std::chrono::seconds(20)) {
    return scheduler_->WaitForCounts([](uint32_t queued, uint32_t running, uint32_t) {
      return queued == 0 && running == 0;
    }, timeout);
  }

  storage::testing::TempDir dir_;
  std::unique_ptr<storage::SetCache> cache_;
  Metrics metrics_;
  std::shared_ptr<Gate> gate_ = std::make_shared<Gate>();
  std::unique_ptr<Scheduler> scheduler_;
};

}  // namespace alignset::server::testing

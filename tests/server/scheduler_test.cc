#include "server/scheduler.h"

#include <gtest/gtest.h>

#include <thread>

#include "tests/server/scheduler_fixture.h"

namespace alignset::server {
namespace {

using namespace std::chrono_literals;

class SchedulerTest : public testing::SchedulerFixture {
 protected:
  void Start(int workers, int max_queue, int max_iterations) {
    Scheduler::Options o;
    o.workers = workers;
    o.max_queue = max_queue;
    o.producer.optimizer.max_iterations = max_iterations;
    // One optimization per key (the key lineage, which starts a key's
    // ancestors first, has its own end-to-end tests).
    o.producer.optimizer.warm_budget_fraction = 0.0;
    o.producer.optimizer.progress_every = 1;
    StartWith(o);
  }
  static void WaitDone(const Ticket& t) { SchedulerFixture::WaitDone(t, 600); }
};

TEST_F(SchedulerTest, ConcurrentRequestsForOneKeyShareOneOptimization) {
  gate_->Close();
  Start(/*workers=*/2, 64, 20);
  const storage::SetKey key = Key(64, 17);
  std::vector<std::unique_ptr<Ticket>> tickets(16);
  std::vector<std::thread> threads;
  for (int i = 0; i < 16; ++i) {
    threads.emplace_back([&, i] { tickets[i] = MustAcquire(key, Priority::kInteractive); });
  }
  for (auto& t : threads) t.join();
  gate_->Open();
  for (auto& t : tickets) {
    ASSERT_NE(t, nullptr);
    WaitDone(*t);
  }
  auto first = tickets[0]->Result();
  ASSERT_TRUE(first.ok()) << first.status().message();
  for (auto& t : tickets) {
    auto r = t->Result();
    ASSERT_TRUE(r.ok());
    EXPECT_EQ(r->get(), first->get());  // the very same entry
    EXPECT_FALSE(t->from_cache());
  }
  EXPECT_EQ(metrics_.optimizations_started.load(), 1u);
  EXPECT_EQ(metrics_.optimizations_completed.load(), 1u);
  EXPECT_EQ(metrics_.shared_waits.load(), 15u);
  // Stored before anyone saw it, and served from memory afterwards.
  EXPECT_TRUE(cache_->Contains(key).value());
  auto again = MustAcquire(key, Priority::kInteractive);
  EXPECT_TRUE(again->Done());
  EXPECT_TRUE(again->from_cache());
  EXPECT_EQ(metrics_.cache_hits_memory.load(), 1u);
}

TEST_F(SchedulerTest, InteractiveRunsBeforeBatchAndPromotesSharedBatchJobs) {
  gate_->Close();
  Start(/*workers=*/1, 64, 20);
  auto running = MustAcquire(Key(64, 0), Priority::kBatch);
  gate_->AwaitArrivals(1);  // the worker holds it: everything else queues
  auto b1 = MustAcquire(Key(64, 1), Priority::kBatch);
  auto b2 = MustAcquire(Key(64, 2), Priority::kBatch);
  auto i1 = MustAcquire(Key(64, 3), Priority::kInteractive);
  EXPECT_EQ(running->View().state, JobView::State::kRunning);
  EXPECT_EQ(i1->View().queue_position, 0u);
  EXPECT_EQ(b1->View().queue_position, 1u);
  EXPECT_EQ(b2->View().queue_position, 2u);
  // An interactive request joining b2 lifts it among the interactive jobs,
  // where it keeps its arrival order: ahead of i1, which came later.
  auto i2 = MustAcquire(Key(64, 2), Priority::kInteractive);
  EXPECT_EQ(b2->View().queue_position, 0u);
  EXPECT_EQ(i1->View().queue_position, 1u);
  EXPECT_EQ(b1->View().queue_position, 2u);
  EXPECT_EQ(scheduler_->queue_length(), 3u);
  gate_->Open();
  for (auto* t : {&running, &b1, &b2, &i1, &i2}) WaitDone(**t);
  EXPECT_EQ(metrics_.optimizations_completed.load(), 4u);
}

TEST_F(SchedulerTest, LastWaiterLeavingCancelsTheOptimizationAndStoresNothing) {
  gate_->Close();
  Start(/*workers=*/1, 64, 1000000);
  const storage::SetKey key = Key(64, 5);
  auto a = MustAcquire(key, Priority::kInteractive);
  auto b = MustAcquire(key, Priority::kInteractive);
  gate_->AwaitArrivals(1);
  EXPECT_EQ(a->View().state, JobView::State::kRunning);
  a.reset();  // one waiter left: the job goes on
  gate_->Open();
  const int at = b->View().progress.iteration;
  const JobView later = WaitIterations(*b, at + 2);  // iterations run after `a` left
  EXPECT_GE(later.progress.iteration, at + 2);
  EXPECT_EQ(later.state, JobView::State::kRunning);
  EXPECT_EQ(metrics_.optimizations_cancelled.load(), 0u);
  b.reset();  // none left: stopped at the next progress callback
  EXPECT_TRUE(WaitIdle());
  EXPECT_EQ(scheduler_->running(), 0u);
  EXPECT_EQ(metrics_.optimizations_cancelled.load(), 1u);
  EXPECT_EQ(metrics_.optimizations_completed.load(), 0u);
  EXPECT_FALSE(cache_->Contains(key).value());
}

TEST_F(SchedulerTest, QueuedJobWithoutWaitersLeavesTheQueue) {
  gate_->Close();
  Start(/*workers=*/1, 64, 20);
  auto running = MustAcquire(Key(64, 0), Priority::kInteractive);
  gate_->AwaitArrivals(1);
  auto queued = MustAcquire(Key(64, 9), Priority::kInteractive);
  EXPECT_EQ(scheduler_->queue_length(), 1u);
  queued.reset();
  EXPECT_EQ(scheduler_->queue_length(), 0u);
  EXPECT_EQ(metrics_.optimizations_cancelled.load(), 1u);
  gate_->Open();
  WaitDone(*running);
  EXPECT_EQ(metrics_.optimizations_started.load(), 1u);
}

TEST_F(SchedulerTest, FullQueueRefusesNewKeysButAdmitsJoiners) {
  gate_->Close();
  Start(/*workers=*/1, /*max_queue=*/2, 20);
  auto running = MustAcquire(Key(64, 0), Priority::kInteractive);
  gate_->AwaitArrivals(1);
  auto q1 = MustAcquire(Key(64, 1), Priority::kInteractive);
  auto q2 = MustAcquire(Key(64, 2), Priority::kBatch);
  auto refused = scheduler_->Acquire(Key(64, 3), Priority::kInteractive);
  ASSERT_FALSE(refused.ok());
  EXPECT_EQ(refused.status().code(), Status::Code::kResourceExhausted);
  EXPECT_EQ(metrics_.rejected_queue_full.load(), 1u);
  auto joiner = scheduler_->Acquire(Key(64, 2), Priority::kInteractive);
  EXPECT_TRUE(joiner.ok());
  gate_->Open();
  WaitDone(**joiner);
  EXPECT_TRUE((*joiner)->Result().ok());
}

TEST_F(SchedulerTest, ShutdownEndsQueuedJobsAsUnavailable) {
  gate_->Close();
  Start(/*workers=*/1, 64, 1000000);
  auto running = MustAcquire(Key(64, 0), Priority::kInteractive);
  gate_->AwaitArrivals(1);
  auto queued = MustAcquire(Key(64, 1), Priority::kInteractive);
  scheduler_->BeginShutdown();
  ASSERT_TRUE(queued->Done());
  EXPECT_EQ(queued->Result().status().code(), Status::Code::kUnavailable);
  gate_->Open();
  scheduler_->Shutdown();
  EXPECT_TRUE(running->Done());
  EXPECT_FALSE(running->Result().ok());
  auto after = scheduler_->Acquire(Key(64, 2), Priority::kInteractive);
  EXPECT_EQ(after.status().code(), Status::Code::kUnavailable);
}

TEST_F(SchedulerTest, StoredSetIsAHitAfterRestart) {
  Start(/*workers=*/1, 64, 20);
  const storage::SetKey key = Key(64, 44);
  auto first = MustAcquire(key, Priority::kInteractive);
  WaitDone(*first);
  auto a = first->Result();
  ASSERT_TRUE(a.ok());
  const PointSet points = (*a)->record().points;
  scheduler_.reset();
  Start(/*workers=*/1, 64, 20);  // a fresh in-memory cache
  auto second = MustAcquire(key, Priority::kInteractive);
  ASSERT_TRUE(second->Done());
  EXPECT_TRUE(second->from_cache());
  EXPECT_EQ((*second->Result())->record().points, points);
  EXPECT_EQ(metrics_.cache_hits_db.load(), 1u);
  EXPECT_EQ(metrics_.optimizations_started.load(), 1u);
}

}  // namespace
}  // namespace alignset::server

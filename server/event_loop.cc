#include "server/event_loop.h"

namespace alignset::server {

EventLoop::EventLoop(std::chrono::milliseconds period, std::function<void()> tick)
    : period_(period), tick_(std::move(tick)), thread_([this] { Run(); }) {}

EventLoop::~EventLoop() { Stop(); }

void EventLoop::Post(std::function<void()> fn) {
  std::lock_guard<std::mutex> lock(mu_);
  if (stopping_) return;
  queue_.push_back(std::move(fn));
  cv_.notify_one();
}

void EventLoop::Stop() {
  {
    std::lock_guard<std::mutex> lock(mu_);
    stopping_ = true;
    cv_.notify_one();
  }
  if (thread_.joinable()) thread_.join();
}

void EventLoop::Run() {
  using Clock = std::chrono::steady_clock;
  auto next_tick = Clock::now() + period_;
  std::unique_lock<std::mutex> lock(mu_);
  for (;;) {
    if (queue_.empty()) {
      if (stopping_) return;
      if (tick_) {
        cv_.wait_until(lock, next_tick, [&] { return stopping_ || !queue_.empty(); });
      } else {
        cv_.wait(lock, [&] { return stopping_ || !queue_.empty(); });
      }
    }
    std::deque<std::function<void()>> batch;
    batch.swap(queue_);
    lock.unlock();
    for (auto& fn : batch) fn();
    if (tick_ && Clock::now() >= next_tick) {
      tick_();
      next_tick = Clock::now() + period_;
    }
    lock.lock();
  }
}

}  // namespace alignset::server

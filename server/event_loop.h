#pragma once

#include <chrono>
#include <condition_variable>
#include <deque>
#include <functional>
#include <mutex>
#include <thread>

namespace alignset::server {

// One thread that runs posted closures in order, plus one periodic closure.
// The callback-API handlers use it for what must not run on gRPC's own
// threads or on an optimization worker: building responses for the waiters
// of a finished job, and pacing the watch streams. One thread for all
// waiting calls, however many there are.
class EventLoop {
 public:
  // `tick` runs every `period` (none when empty).
  EventLoop(std::chrono::milliseconds period, std::function<void()> tick);
  ~EventLoop();  // Stop()
  EventLoop(const EventLoop&) = delete;
  EventLoop& operator=(const EventLoop&) = delete;

  // Runs `fn` on the loop's thread soon; dropped after Stop().
  void Post(std::function<void()> fn);
  // Runs what is posted, then joins the thread.
  void Stop();

 private:
  void Run();

  const std::chrono::milliseconds period_;
  const std::function<void()> tick_;
  std::mutex mu_;
  std::condition_variable cv_;
  std::deque<std::function<void()>> queue_;
  bool stopping_ = false;
  std::thread thread_;
};

}  // namespace alignset::server

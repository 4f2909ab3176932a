#pragma once

#include <chrono>
#include <cstdint>

#include "server/scheduler.h"

namespace alignset::server {

// Decides when a WatchAlignedSet stream sends an event, from the job's view
// at the moment it is asked:
// - a change of state or of queue position goes out at once;
// - new progress goes out at most every `min_interval` (optimizer callbacks
//   can come every few microseconds), and progress that arrived inside that
//   window is sent when it closes, never dropped;
// - whatever happens, the watcher hears something every `heartbeat`: the
//   current progress with its elapsed time (or the queue position), so that
//   a slow iteration at a large N, or the set-up before the first one, does
//   not look like a dead stream.
class WatchPacer {
 public:
  using Clock = std::chrono::steady_clock;
  enum class Send { kNothing, kQueued, kProgress };

  explicit WatchPacer(std::chrono::milliseconds min_interval = std::chrono::milliseconds(100),
                      std::chrono::milliseconds heartbeat = std::chrono::milliseconds(1000))
      : min_interval_(min_interval), heartbeat_(heartbeat) {}

  // What to send for `view` now (kNothing for a done job: the caller sends
  // the set). Records a send as made.
  Send Next(const JobView& view, Clock::time_point now);
  // How long the caller may wait for a change before asking again.
  std::chrono::milliseconds Wait(Clock::time_point now) const;

 private:
  const std::chrono::milliseconds min_interval_;
  const std::chrono::milliseconds heartbeat_;
  bool sent_any_ = false;
  JobView::State sent_state_ = JobView::State::kDone;
  size_t sent_position_ = 0;
  uint64_t sent_version_ = 0;
  bool pending_ = false;  // a change not sent yet (inside the window)
  Clock::time_point last_sent_{};
};

}  // namespace alignset::server

#include "server/watch_pacer.h"

#include <algorithm>

namespace alignset::server {

WatchPacer::Send WatchPacer::Next(const JobView& view, Clock::time_point now) {
  if (view.state == JobView::State::kDone) return Send::kNothing;
  const bool first_in_state = !sent_any_ || view.state != sent_state_;
  bool send = false;
  if (view.state == JobView::State::kQueued) {
    send = first_in_state || view.queue_position != sent_position_ || now - last_sent_ >= heartbeat_;
  } else {
    const bool news = view.version != sent_version_;
    pending_ = news;
    send = first_in_state || (news && now - last_sent_ >= min_interval_) ||
           now - last_sent_ >= heartbeat_;
  }
  if (!send) return Send::kNothing;
  sent_any_ = true;
  sent_state_ = view.state;
  sent_position_ = view.queue_position;
  sent_version_ = view.version;
  pending_ = false;
  last_sent_ = now;
  return view.state == JobView::State::kQueued ? Send::kQueued : Send::kProgress;
}

std::chrono::milliseconds WatchPacer::Wait(Clock::time_point now) const {
  using std::chrono::duration_cast;
  using std::chrono::milliseconds;
  if (!sent_any_) return milliseconds(0);
  const auto since = duration_cast<milliseconds>(now - last_sent_);
  const milliseconds due = pending_ ? min_interval_ - since : heartbeat_ - since;
  return std::clamp(due, milliseconds(1), heartbeat_);
}

}  // namespace alignset::server

// WatchAlignedSet: queued position, progress and then the set, on a
// callback write reactor paced by the service's event loop.
#include "server/service.h"

#include <spdlog/spdlog.h>

#include <memory>
#include <mutex>

#include "server/log_text.h"
#include "server/service_internal.h"
#include "server/validation.h"
#include "server/watch_pacer.h"

namespace alignset::server {
using service_internal::Clock;
using service_internal::ClientGone;
using service_internal::Since;

// A WatchAlignedSet stream. Holds no thread: the event loop calls Tick()
// every 100 ms (and at once when the job is done), and Tick writes what the
// pacer says is due, one message at a time.
class WatchCall final : public grpc::ServerWriteReactor<v1::WatchEvent>,
                        public std::enable_shared_from_this<WatchCall> {
 public:
  WatchCall(AlignSetService* service, grpc::CallbackServerContext* ctx, Canonicalization canon,
            storage::SetKey key, std::unique_ptr<Ticket> ticket, Clock::time_point t0)
      : service_(service), ctx_(ctx), canon_(std::move(canon)), key_(std::move(key)),
        ticket_(std::move(ticket)), t0_(t0) {}

  grpc::ServerWriteReactor<v1::WatchEvent>* Start() {
    // What the handler's thread made here reaches the callbacks, which gRPC
    // runs on other threads, through mu_, not only through gRPC's own
    // ordering, which ThreadSanitizer cannot see. (A tick posted here waits
    // for it; nothing holding the watch list or the scheduler takes mu_.)
    std::lock_guard<std::mutex> lock(mu_);
    self_ = shared_from_this();
    service_->AddWatch(self_);
    std::weak_ptr<WatchCall> weak = self_;
    EventLoop* loop = service_->loop_.get();
    auto tick = [weak] {
      if (auto call = weak.lock()) call->Tick();
    };
    ticket_->OnDone([loop, tick] { loop->Post(tick); });
    loop->Post(tick);  // the first event (queue position, or the set) at once
    return this;
  }

  // What is due now, if nothing is being written.
  void Tick() {
    std::lock_guard<std::mutex> lock(mu_);
    if (ended_ || writing_) return;
    const JobView v = ticket_->View();
    ev_.Clear();
    if (v.state == JobView::State::kDone) {
      auto entry = ticket_->Result();
      if (!entry.ok()) return EndLocked(ToGrpc(entry.status()));
      service_->FillSet(canon_, key_, **entry, ticket_->from_cache(), ev_.mutable_set());
      last_ = true;
    } else {
      switch (pacer_.Next(v, Clock::now())) {
        case WatchPacer::Send::kNothing: return;
        case WatchPacer::Send::kQueued:
          ev_.mutable_queued()->set_position(static_cast<uint32_t>(v.queue_position));
          break;
        case WatchPacer::Send::kProgress: {
          v1::Progress* p = ev_.mutable_progress();
          p->set_iteration(v.progress.iteration);
          p->set_max_iterations(v.progress.max_iterations);
          p->set_loss(v.progress.loss);
          p->set_learning_rate(v.progress.learning_rate);
          p->set_elapsed_seconds(v.elapsed_seconds);
          break;
        }
      }
    }
    writing_ = true;
    StartWrite(&ev_);
  }

  void OnWriteDone(bool ok) override {
    std::lock_guard<std::mutex> lock(mu_);
    writing_ = false;
    if (ended_) return;
    if (!ok) return EndLocked(ClientGone(ctx_));
    if (last_) return EndLocked(grpc::Status::OK);
  }

  void OnCancel() override {
    std::lock_guard<std::mutex> lock(mu_);
    cancelled_ = true;
    // With a write in flight, OnWriteDone(false) ends the stream.
    if (!writing_) EndLocked(ClientGone(ctx_));
  }

  void OnDone() override {
    { std::lock_guard<std::mutex> published(mu_); }  // after Start and every callback
    service_->RemoveWatch(this);
    ticket_.reset();
    service_->ReturnWaitingSlot();
    self_.reset();
  }

 private:
  void EndLocked(const grpc::Status& s) {
    if (ended_) return;
    ended_ = true;
    service_->metrics_->latency_watch.Observe(Since(t0_));
    Finish(s);
  }

  AlignSetService* const service_;
  grpc::CallbackServerContext* const ctx_;
  const Canonicalization canon_;
  const storage::SetKey key_;
  std::unique_ptr<Ticket> ticket_;
  const Clock::time_point t0_;
  std::mutex mu_;
  WatchPacer pacer_;
  v1::WatchEvent ev_;  // the message in flight: valid until OnWriteDone
  bool writing_ = false;
  bool last_ = false;
  bool ended_ = false;
  bool cancelled_ = false;
  std::shared_ptr<WatchCall> self_;
};

void AlignSetService::AddWatch(const std::shared_ptr<WatchCall>& call) {
  std::lock_guard<std::mutex> lock(watches_mu_);
  watches_[call.get()] = call;
}

void AlignSetService::RemoveWatch(const WatchCall* call) {
  std::lock_guard<std::mutex> lock(watches_mu_);
  watches_.erase(call);
}

void AlignSetService::TickWatches() {
  std::vector<std::shared_ptr<WatchCall>> live;
  {
    std::lock_guard<std::mutex> lock(watches_mu_);
    live.reserve(watches_.size());
    for (const auto& [ptr, weak] : watches_) {
      if (auto call = weak.lock()) live.push_back(std::move(call));
    }
  }
  for (const auto& call : live) call->Tick();
}

grpc::ServerWriteReactor<v1::WatchEvent>* AlignSetService::WatchAlignedSet(
    grpc::CallbackServerContext* ctx, const v1::AlignedSetRequest* req) {
  const auto t0 = Clock::now();
  // Refusals before the stream starts: a reactor that only finishes.
  class Refusal final : public grpc::ServerWriteReactor<v1::WatchEvent> {
   public:
    explicit Refusal(const grpc::Status& s) { Finish(s); }
    void OnDone() override { delete this; }
  };
  auto refuse = [&](const grpc::Status& s) {
    metrics_->latency_watch.Observe(Since(t0));
    return new Refusal(s);
  };
  if (auto a = Authorize(ctx); !a.ok()) return refuse(a);
  metrics_->requests_watch.fetch_add(1, std::memory_order_relaxed);
  auto canon = Canonicalize(*req);
  if (!canon.ok()) return refuse(Invalid(canon.status(), "WatchAlignedSet"));
  auto key_or = KeyOf(*req, *canon);
  if (!key_or.ok()) return refuse(Invalid(key_or.status(), "WatchAlignedSet"));
  const storage::SetKey key = std::move(key_or).value();
  auto ticket = scheduler_->Acquire(key, Priority::kInteractive, ctx->peer());
  if (!ticket.ok()) return refuse(ToGrpc(ticket.status()));
  if (!TakeWaitingSlot()) {
    return refuse(grpc::Status(grpc::StatusCode::RESOURCE_EXHAUSTED,
                               "too many calls are waiting for optimizations (" +
                                   std::to_string(config_.max_waiting_calls) +
                                   ", --max-waiting-calls); retry later"));
  }
  auto call = std::make_shared<WatchCall>(this, ctx, std::move(canon).value(), key,
                                          std::move(ticket).value(), t0);
  return call->Start();
}
}  // namespace alignset::server

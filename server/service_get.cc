// GetAlignedSet: a hit is answered at once; a call that waits for an
// optimization holds no thread (GetCall, a callback reactor).
#include "server/service.h"

#include <spdlog/spdlog.h>

#include <memory>
#include <mutex>

#include "server/log_text.h"
#include "server/service_internal.h"
#include "server/validation.h"

namespace alignset::server {
using service_internal::Clock;
using service_internal::ClientGone;
using service_internal::Since;

// A GetAlignedSet call waiting for its optimization. It holds no thread:
// the ticket's done callback posts Complete() to the event loop, and gRPC's
// OnCancel ends it early when the client leaves. Owned by itself from Start
// to OnDone; closures elsewhere hold weak pointers.
class GetCall final : public grpc::ServerUnaryReactor, public std::enable_shared_from_this<GetCall> {
 public:
  GetCall(AlignSetService* service, grpc::CallbackServerContext* ctx, v1::AlignedSetResponse* resp,
          Canonicalization canon, storage::SetKey key, std::unique_ptr<Ticket> ticket,
          Clock::time_point t0)
      : service_(service), ctx_(ctx), resp_(resp), canon_(std::move(canon)), key_(std::move(key)),
        ticket_(std::move(ticket)), t0_(t0) {}

  grpc::ServerUnaryReactor* Start() {
    // What the handler's thread made here reaches OnCancel and OnDone, which
    // gRPC runs on other threads, through mu_ (Claim, Published), not only
    // through gRPC's own ordering, which ThreadSanitizer cannot see.
    std::lock_guard<std::mutex> lock(mu_);
    self_ = shared_from_this();
    std::weak_ptr<GetCall> weak = self_;
    EventLoop* loop = service_->loop_.get();
    ticket_->OnDone([weak, loop] {
      loop->Post([weak] {
        if (auto call = weak.lock()) call->Complete();
      });
    });
    return this;
  }

  void OnCancel() override {
    if (!Claim()) return;
    grpc::Status s = ClientGone(ctx_);
    spdlog::info("GetAlignedSet {}: client stopped waiting ({})", KeyString(key_), s.error_message());
    End(s);
  }

  void OnDone() override {
    Published();
    ticket_.reset();  // withdraws the waiter if the job is still on
    service_->ReturnWaitingSlot();
    self_.reset();
  }

 private:
  // Orders this thread after Start and every Claim.
  void Published() { std::lock_guard<std::mutex> lock(mu_); }
  // The first of Complete and OnCancel to get here finishes the call.
  bool Claim() {
    std::lock_guard<std::mutex> lock(mu_);
    if (claimed_) return false;
    claimed_ = true;
    return true;
  }
  void Complete() {
    if (!Claim()) return;
    auto entry = ticket_->Result();
    if (!entry.ok()) return End(ToGrpc(entry.status()));
    service_->FillSet(canon_, key_, **entry, ticket_->from_cache(), resp_);
    End(grpc::Status::OK);
  }
  void End(const grpc::Status& s) {
    service_->metrics_->latency_get.Observe(Since(t0_));
    Finish(s);
  }

  AlignSetService* const service_;
  grpc::CallbackServerContext* const ctx_;
  v1::AlignedSetResponse* const resp_;
  const Canonicalization canon_;
  const storage::SetKey key_;
  std::unique_ptr<Ticket> ticket_;
  const Clock::time_point t0_;
  std::mutex mu_;
  bool claimed_ = false;
  std::shared_ptr<GetCall> self_;
};

grpc::ServerUnaryReactor* AlignSetService::GetAlignedSet(grpc::CallbackServerContext* ctx,
                                                         const v1::AlignedSetRequest* req,
                                                         v1::AlignedSetResponse* resp) {
  const auto t0 = Clock::now();
  auto finish = [&](const grpc::Status& s) {
    metrics_->latency_get.Observe(Since(t0));
    grpc::ServerUnaryReactor* r = ctx->DefaultReactor();
    r->Finish(s);
    return r;
  };
  if (auto a = Authorize(ctx); !a.ok()) return finish(a);
  metrics_->requests_get.fetch_add(1, std::memory_order_relaxed);
  auto canon = Canonicalize(*req);
  if (!canon.ok()) return finish(Invalid(canon.status(), "GetAlignedSet"));
  auto key_or = KeyOf(*req, *canon);
  if (!key_or.ok()) return finish(Invalid(key_or.status(), "GetAlignedSet"));
  const storage::SetKey key = std::move(key_or).value();
  auto ticket = scheduler_->Acquire(key, Priority::kInteractive, ctx->peer());
  if (!ticket.ok()) return finish(ToGrpc(ticket.status()));
  if ((*ticket)->Done()) {
    auto entry = (*ticket)->Result();
    if (!entry.ok()) return finish(ToGrpc(entry.status()));
    const bool from_cache = (*ticket)->from_cache();
    FillSet(*canon, key, **entry, from_cache, resp);
    // Hits are the hot path: logged only at debug level.
    spdlog::debug("served {} as {} ({})", KeyString(key), ToString(canon->ops),
                  from_cache ? "hit" : "optimized");
    return finish(grpc::Status::OK);
  }
  if (!TakeWaitingSlot()) {
    return finish(grpc::Status(grpc::StatusCode::RESOURCE_EXHAUSTED,
                               "too many calls are waiting for optimizations (" +
                                   std::to_string(config_.max_waiting_calls) +
                                   ", --max-waiting-calls); retry later"));
  }
  auto call = std::make_shared<GetCall>(this, ctx, resp, std::move(canon).value(), key,
                                        std::move(ticket).value(), t0);
  spdlog::debug("GetAlignedSet {} waits for its optimization", KeyString(key));
  return call->Start();
}
}  // namespace alignset::server

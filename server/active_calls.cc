#include "server/active_calls.h"

namespace alignset::server {

// One per call: gRPC creates it with the call's ServerRpcInfo and deletes it
// with the call, after the handler has returned and the status was sent.
class CallCounter : public grpc::experimental::Interceptor {
 public:
  explicit CallCounter(ActiveCalls* calls) : calls_(calls) { calls_->Add(1); }
  ~CallCounter() override { calls_->Add(-1); }
  void Intercept(grpc::experimental::InterceptorBatchMethods* methods) override {
    methods->Proceed();
  }

 private:
  ActiveCalls* calls_;
};

namespace {

class CallCounterFactory : public grpc::experimental::ServerInterceptorFactoryInterface {
 public:
  explicit CallCounterFactory(ActiveCalls* calls) : calls_(calls) {}
  grpc::experimental::Interceptor* CreateServerInterceptor(
      grpc::experimental::ServerRpcInfo*) override {
    return new CallCounter(calls_);
  }

 private:
  ActiveCalls* calls_;
};

}  // namespace

std::unique_ptr<grpc::experimental::ServerInterceptorFactoryInterface>
ActiveCalls::InterceptorFactory() {
  return std::make_unique<CallCounterFactory>(this);
}

int ActiveCalls::count() const {
  std::lock_guard<std::mutex> lock(mu_);
  return count_;
}

bool ActiveCalls::WaitUntilNone(std::chrono::steady_clock::time_point deadline) const {
  std::unique_lock<std::mutex> lock(mu_);
  return none_.wait_until(lock, deadline, [&] { return count_ == 0; });
}

void ActiveCalls::Add(int delta) {
  std::lock_guard<std::mutex> lock(mu_);
  count_ += delta;
  if (count_ == 0) none_.notify_all();
}

}  // namespace alignset::server

#pragma once

#include <chrono>
#include <condition_variable>
#include <memory>
#include <mutex>

#include <grpcpp/support/server_interceptor.h>

namespace alignset::server {

// The RPCs a server is running, every service's (AlignSet, health,
// reflection), counted by an interceptor that lives as long as its call.
//
// Why: gRPC's Server::Shutdown(deadline) refuses new calls and gives those
// in flight until the deadline, but (gRPC 1.51) it also waits there for
// every client connection to close, and a C++ client keeps an idle
// connection open after the server's GOAWAY: a server whose renderers stay
// connected, as they do, took its whole grace to stop although no call was
// running. Knowing when the calls are done lets ServerInstance::Shutdown
// close the idle connections then.
class ActiveCalls {
 public:
  // Registered with ServerBuilder::experimental().SetInterceptorCreators;
  // the counter must outlive the server.
  std::unique_ptr<grpc::experimental::ServerInterceptorFactoryInterface> InterceptorFactory();

  int count() const;
  // Waits until no call is running or `deadline` passes; whether none is.
  bool WaitUntilNone(std::chrono::steady_clock::time_point deadline) const;

 private:
  friend class CallCounter;
  void Add(int delta);

  mutable std::mutex mu_;
  mutable std::condition_variable none_;
  int count_ = 0;
};

}  // namespace alignset::server

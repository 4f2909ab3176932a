// Helpers shared by the service's files (server/service*.cc); not an API.
#pragma once

#include <chrono>

#include <grpcpp/grpcpp.h>

namespace alignset::server::service_internal {

using Clock = std::chrono::steady_clock;
// How long a synchronous call waits on a ticket before it looks again at
// its client (cancelled? deadline?).
constexpr auto kPoll = std::chrono::milliseconds(50);

inline double Since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

// Why a call stopped waiting: the deadline passed or the client left.
inline grpc::Status ClientGone(grpc::ServerContextBase* ctx) {
  if (ctx->deadline() <= std::chrono::system_clock::now()) {
    return grpc::Status(grpc::StatusCode::DEADLINE_EXCEEDED,
                        "deadline exceeded while waiting for the optimization");
  }
  return grpc::Status(grpc::StatusCode::CANCELLED, "cancelled by the client");
}

}  // namespace alignset::server::service_internal

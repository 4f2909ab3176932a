#pragma once

#include <memory>
#include <string>

#include "core/util/status.h"
#include "server/config.h"

namespace alignset::server {

// A running alignset server: the SQLite cache, the scheduler and its workers,
// and the gRPC server (the AlignSet service, the standard health service and
// server reflection). No gRPC types in this header, so main and tests stay
// light to compile.
class ServerInstance {
 public:
  // Opens the cache, starts the workers, binds and starts serving.
  static StatusOr<std::unique_ptr<ServerInstance>> Start(const ServerConfig& config);
  ~ServerInstance();

  int port() const;
  const std::string& db_path() const;

  // Graceful stop: health goes NOT_SERVING, new optimizations are refused,
  // queued ones dropped, running ones stopped at their next progress callback
  // (a write in progress finishes), calls get `grace_seconds` to complete,
  // then the workers are joined and the database is closed.
  void Shutdown(double grace_seconds);

  struct Impl;

 private:
  explicit ServerInstance(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace alignset::server

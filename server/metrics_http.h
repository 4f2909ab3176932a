#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>

#include "core/util/status.h"

struct MHD_Daemon;

namespace alignset::server {

// The Prometheus scrape endpoint: GET /metrics on a port of its own, served
// by libmicrohttpd (Debian's libmicrohttpd-dev; no Prometheus C++ client is
// packaged, and the exposition format is a few lines of text). One thread of
// libmicrohttpd's own polls every connection; a scrape renders the text on
// it. With a token (the gRPC service's, --token-file) every request must
// carry "Authorization: Bearer <token>" or gets 401; without one it is open,
// and meant for a pod-internal or private address (docs/operations.md, "Operations").
class MetricsHttpServer {
 public:
  // Listens on `address` (HOST:PORT, port 0: the kernel picks one); every
  // GET /metrics answers render().
  // `token` empty: no authentication. `refused` (may be null) counts the
  // requests refused for a missing or wrong token.
  static StatusOr<std::unique_ptr<MetricsHttpServer>> Start(const std::string& address, std::string token,
                                                            std::function<std::string()> render,
                                                            std::atomic<uint64_t>* refused = nullptr);
  ~MetricsHttpServer();  // stops listening; a scrape in progress completes

  int port() const { return port_; }

 private:
  MetricsHttpServer(std::string token, std::function<std::string()> render, std::atomic<uint64_t>* refused)
      : token_(std::move(token)), render_(std::move(render)), refused_(refused) {}
  friend struct MetricsHttpHandler;

  const std::string token_;
  std::function<std::string()> render_;
  std::atomic<uint64_t>* refused_;
  MHD_Daemon* daemon_ = nullptr;
  int port_ = 0;
};

}  // namespace alignset::server

#pragma once

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
// it. No token: the endpoint says only counts and timings, and is meant for
// a pod-internal or private address (README, "Operations").
class MetricsHttpServer {
 public:
  // Listens on `address` (HOST:PORT, port 0: the kernel picks one); every
  // GET /metrics answers render().
  static StatusOr<std::unique_ptr<MetricsHttpServer>> Start(const std::string& address,
                                                            std::function<std::string()> render);
  ~MetricsHttpServer();  // stops listening; a scrape in progress completes

  int port() const { return port_; }

 private:
  explicit MetricsHttpServer(std::function<std::string()> render) : render_(std::move(render)) {}
  friend struct MetricsHttpHandler;

  std::function<std::string()> render_;
  MHD_Daemon* daemon_ = nullptr;
  int port_ = 0;
};

}  // namespace alignset::server

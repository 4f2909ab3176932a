#pragma once

#include <string>

#include "core/util/status.h"

namespace alignset::server {

// A listening address as gRPC takes it, checked before gRPC sees it: gRPC
// reduces an out-of-range port modulo 65536 (":80000" listens on 14464) and
// takes a missing port as 443, so both are refused here. Accepted forms:
// "host:port" and "[ipv6]:port" with a decimal port in 0..65535 (0: the
// kernel picks one), and "unix:PATH" / "unix-abstract:NAME".
struct ListenAddress {
  std::string host;  // empty for unix sockets
  int port = 0;
  bool unix_socket = false;
};
StatusOr<ListenAddress> ParseListenAddress(const std::string& text, const std::string& what);

// Why `text` cannot be bound, in one phrase ("127.0.0.1:50051 is already in
// use (another server?)"), found by binding a plain socket the way the
// server would; empty when the probe binds fine or the address is not TCP.
// Only called after the real bind failed, to explain it.
std::string DescribeBindFailure(const std::string& text);

}  // namespace alignset::server

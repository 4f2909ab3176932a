#include "server/listen_address.h"

#include <netdb.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "core/util/number_text.h"

namespace alignset::server {

StatusOr<ListenAddress> ParseListenAddress(const std::string& text, const std::string& what) {
  ListenAddress a;
  if (text.rfind("unix:", 0) == 0 || text.rfind("unix-abstract:", 0) == 0) {
    if (text.size() == text.find(':') + 1) return Status::InvalidArgument(what + " '" + text + "' names no socket");
    a.unix_socket = true;
    return a;
  }
  const size_t colon = text.rfind(':');
  if (colon == std::string::npos) {
    return Status::InvalidArgument(what + " '" + text + "' has no port (HOST:PORT, [IPV6]:PORT or unix:PATH)");
  }
  a.host = text.substr(0, colon);
  const std::string port = text.substr(colon + 1);
  if (a.host.empty()) return Status::InvalidArgument(what + " '" + text + "' has no host (use 0.0.0.0 or [::] for every interface)");
  if (a.host.front() == '[') {
    if (a.host.back() != ']' || a.host.size() < 3) {
      return Status::InvalidArgument(what + " '" + text + "': an IPv6 host goes in brackets, [::1]:PORT");
    }
    a.host = a.host.substr(1, a.host.size() - 2);
  } else if (a.host.find(':') != std::string::npos) {
    return Status::InvalidArgument(what + " '" + text + "': an IPv6 host goes in brackets, [::1]:PORT");
  }
  for (char c : port) {
    if (c < '0' || c > '9') {
      return Status::InvalidArgument(what + " '" + text + "': port '" + port + "' is not a number in 0..65535");
    }
  }
  auto p = ParseInt(port, what + " port", 0, 65535);
  if (!p.ok()) {
    return Status::InvalidArgument(what + " '" + text + "': port " + port + " is outside 0..65535");
  }
  a.port = static_cast<int>(*p);
  return a;
}

std::string DescribeBindFailure(const std::string& text) {
  auto a = ParseListenAddress(text, "address");
  if (!a.ok() || a->unix_socket) return "";
  addrinfo hints{};
  hints.ai_family = AF_UNSPEC;
  hints.ai_socktype = SOCK_STREAM;
  hints.ai_flags = AI_PASSIVE;
  addrinfo* found = nullptr;
  const std::string port = std::to_string(a->port);
  if (const int rc = getaddrinfo(a->host.c_str(), port.c_str(), &hints, &found); rc != 0) {
    return "cannot resolve '" + a->host + "': " + gai_strerror(rc);
  }
  std::string why;
  for (addrinfo* ai = found; ai != nullptr && why.empty(); ai = ai->ai_next) {
    const int fd = socket(ai->ai_family, ai->ai_socktype | SOCK_CLOEXEC, ai->ai_protocol);
    if (fd < 0) continue;
    // As gRPC does: SO_REUSEADDR, so a port in TIME_WAIT is not "in use".
    const int one = 1;
    setsockopt(fd, SOL_SOCKET, SO_REUSEADDR, &one, sizeof(one));
    if (bind(fd, ai->ai_addr, ai->ai_addrlen) != 0) {
      const int err = errno;
      if (err == EADDRINUSE) {
        why = text + " is already in use (is another alignset-server listening there?)";
      } else if (err == EACCES) {
        why = "no permission to bind " + text + " (ports below 1024 need privileges)";
      } else if (err == EADDRNOTAVAIL) {
        why = a->host + " is not an address of this machine";
      } else {
        why = "bind " + text + ": " + std::strerror(err);
      }
    }
    close(fd);
  }
  freeaddrinfo(found);
  return why;
}

}  // namespace alignset::server

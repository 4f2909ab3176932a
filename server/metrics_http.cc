#include "server/metrics_http.h"

#include <microhttpd.h>
#include <netdb.h>
#include <sys/socket.h>

#include <cstring>

#include "server/bearer_token.h"
#include "server/listen_address.h"

namespace alignset::server {

struct MetricsHttpHandler {
  static MHD_Result Answer(unsigned int code, const char* content_type,
                           const std::string& body, MHD_Connection* connection) {
    MHD_Response* response =
        MHD_create_response_from_buffer(body.size(), const_cast<char*>(body.data()), MHD_RESPMEM_MUST_COPY);
    if (response == nullptr) return MHD_NO;
    MHD_add_response_header(response, MHD_HTTP_HEADER_CONTENT_TYPE, content_type);
    if (code == MHD_HTTP_METHOD_NOT_ALLOWED) MHD_add_response_header(response, MHD_HTTP_HEADER_ALLOW, "GET, HEAD");
    if (code == MHD_HTTP_UNAUTHORIZED) {
      MHD_add_response_header(response, MHD_HTTP_HEADER_WWW_AUTHENTICATE, "Bearer realm=\"alignset\"");
    }
    const MHD_Result r = MHD_queue_response(connection, code, response);
    MHD_destroy_response(response);
    return r;
  }

  static MHD_Result Handle(void* cls, MHD_Connection* connection, const char* url, const char* method,
                           const char* /*version*/, const char* /*upload_data*/,
                           size_t* upload_data_size, void** /*con_cls*/) {
    auto* self = static_cast<MetricsHttpServer*>(cls);
    if (!self->token_.empty()) {
      // Before anything else, the method and path included: without the
      // token a client learns nothing but that one is needed.
      const char* auth = MHD_lookup_connection_value(connection, MHD_HEADER_KIND, MHD_HTTP_HEADER_AUTHORIZATION);
      if (auth == nullptr || !BearerTokenMatches(auth, self->token_)) {
        if (*upload_data_size != 0) {
          *upload_data_size = 0;
          return MHD_YES;
        }
        if (self->refused_ != nullptr) self->refused_->fetch_add(1, std::memory_order_relaxed);
        return Answer(MHD_HTTP_UNAUTHORIZED, "text/plain; charset=utf-8",
                      auth == nullptr ? "this endpoint requires 'Authorization: Bearer <token>'\n"
                                      : "invalid bearer token\n",
                      connection);
      }
    }
    const bool get = std::strcmp(method, MHD_HTTP_METHOD_GET) == 0 ||
                     std::strcmp(method, MHD_HTTP_METHOD_HEAD) == 0;
    if (!get) {
      if (*upload_data_size != 0) {  // a body we do not read: let it pass
        *upload_data_size = 0;
        return MHD_YES;
      }
      return Answer(MHD_HTTP_METHOD_NOT_ALLOWED, "text/plain; charset=utf-8",
                    "only GET /metrics is served here\n", connection);
    }
    if (std::strcmp(url, "/metrics") != 0) {
      return Answer(MHD_HTTP_NOT_FOUND, "text/plain; charset=utf-8",
                    "not found: the Prometheus metrics are at /metrics\n", connection);
    }
    return Answer(MHD_HTTP_OK, "text/plain; version=0.0.4; charset=utf-8", self->render_(), connection);
  }
};

StatusOr<std::unique_ptr<MetricsHttpServer>> MetricsHttpServer::Start(const std::string& address, std::string token,
                                                                      std::function<std::string()> render,
                                                                      std::atomic<uint64_t>* refused) {
  auto a = ParseListenAddress(address, "--metrics-listen");
  if (!a.ok()) return a.status();
  if (a->unix_socket) return Status::InvalidArgument("--metrics-listen takes HOST:PORT");
  addrinfo hints{};
  hints.ai_family = AF_UNSPEC;
  hints.ai_socktype = SOCK_STREAM;
  hints.ai_flags = AI_PASSIVE | AI_NUMERICSERV;
  addrinfo* found = nullptr;
  const std::string port = std::to_string(a->port);
  if (const int rc = getaddrinfo(a->host.c_str(), port.c_str(), &hints, &found); rc != 0) {
    return Status::InvalidArgument("--metrics-listen " + address + ": cannot resolve '" + a->host +
                                   "': " + gai_strerror(rc));
  }
  std::unique_ptr<MetricsHttpServer> server(new MetricsHttpServer(std::move(token), std::move(render), refused));
  sockaddr_storage sa{};
  std::memcpy(&sa, found->ai_addr, found->ai_addrlen);
  const bool ipv6 = found->ai_family == AF_INET6;
  freeaddrinfo(found);
  unsigned int flags = MHD_USE_INTERNAL_POLLING_THREAD | MHD_USE_POLL;
  if (ipv6) flags |= MHD_USE_IPv6;
  // A handful of scrapers at most: connections are capped, and a slow or
  // idle one is dropped after 10 s.
  server->daemon_ = MHD_start_daemon(flags, static_cast<uint16_t>(a->port), nullptr, nullptr,
                                     &MetricsHttpHandler::Handle, server.get(),
                                     MHD_OPTION_SOCK_ADDR, reinterpret_cast<sockaddr*>(&sa),
                                     MHD_OPTION_CONNECTION_LIMIT, 32u,
                                     MHD_OPTION_CONNECTION_TIMEOUT, 10u, MHD_OPTION_END);
  if (server->daemon_ == nullptr) {
    const std::string why = DescribeBindFailure(address);
    return Status::Unavailable("cannot serve metrics on " + address + (why.empty() ? "" : ": " + why));
  }
  const MHD_DaemonInfo* info = MHD_get_daemon_info(server->daemon_, MHD_DAEMON_INFO_BIND_PORT);
  server->port_ = info != nullptr ? info->port : a->port;
  return server;
}

MetricsHttpServer::~MetricsHttpServer() {
  if (daemon_ != nullptr) MHD_stop_daemon(daemon_);
}

}  // namespace alignset::server

#include "cli/service_options.h"

#include <fstream>

namespace alignset::cli {

void AddServiceOptions(CLI::App* command, ServiceOptions* o) {
  const std::string group = "Server";
  command->add_option("--server", o->server, "server address host:port")
      ->envname("ALIGNSET_SERVER")
      ->capture_default_str()
      ->group(group);
  command->add_option("--tls-ca", o->tls_ca, "trust this PEM root certificate and use TLS")
      ->group(group);
  command->add_option("--tls-server-name", o->tls_server_name,
                      "name to check in the server's certificate")
      ->group(group);
  command->add_option("--token-file", o->token_file, "send the file's first line as bearer token")
      ->envname("ALIGNSET_TOKEN_FILE")
      ->group(group);
  command->add_option("--timeout", o->timeout_seconds, "deadline of each unary call in seconds (0: none)")
      ->check(FiniteIn(0, 1e9))
      ->group(group);
  command->add_option("--connect-timeout", o->connect_timeout_seconds,
                      "how long a call waits for the server to accept the connection "
                      "(a restart, a full backlog) before it fails")
      ->check(FiniteIn(0, 1e9))
      ->capture_default_str()
      ->group(group);
}

StatusOr<ConnectOptions> ResolveConnectOptions(const ServiceOptions& options) {
  ConnectOptions o;
  o.address = options.server;
  o.tls_ca_file = options.tls_ca;
  o.tls_server_name = options.tls_server_name;
  o.timeout_seconds = options.timeout_seconds;
  o.connect_timeout_seconds = options.connect_timeout_seconds;
  if (!options.token_file.empty()) {
    std::ifstream in(options.token_file);
    if (!in) return Status::InvalidArgument("cannot read --token-file " + options.token_file);
    std::string line;
    std::getline(in, line);
    const auto b = line.find_first_not_of(" \t\r");
    const auto e = line.find_last_not_of(" \t\r");
    if (b == std::string::npos) {
      return Status::InvalidArgument("--token-file " + options.token_file + " holds no token");
    }
    o.token = line.substr(b, e - b + 1);
  }
  return o;
}

StatusOr<std::unique_ptr<ServiceClient>> Connect(const ServiceOptions& options) {
  auto o = ResolveConnectOptions(options);
  if (!o.ok()) return o.status();
  return ServiceClient::Connect(*o);
}

}  // namespace alignset::cli

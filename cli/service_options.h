#pragma once

#include <memory>
#include <string>

#include "cli/cli_app.h"
#include <alignset/client.h>

namespace alignset::cli {

// Options shared by the subcommands that talk to a server:
//   --server ADDR       (default $ALIGNSET_SERVER, else 127.0.0.1:50051)
//   --tls-ca FILE       trust this root certificate and use TLS
//   --tls-server-name   name to check in the server's certificate
//   --token-file FILE   send its first line as the bearer token
//                       (default $ALIGNSET_TOKEN_FILE)
//   --timeout SECONDS   deadline of each unary call (default: none)
//   --connect-timeout S how long a call waits for the connection (default 2)
struct ServiceOptions {
  std::string server = kDefaultServerAddress;
  std::string tls_ca;
  std::string tls_server_name;
  std::string token_file;
  double timeout_seconds = 0.0;
  double connect_timeout_seconds = ConnectOptions{}.connect_timeout_seconds;
};

void AddServiceOptions(CLI::App* command, ServiceOptions* options);
// Reads the token file; a missing or empty one is an error.
StatusOr<ConnectOptions> ResolveConnectOptions(const ServiceOptions& options);
StatusOr<std::unique_ptr<ServiceClient>> Connect(const ServiceOptions& options);

}  // namespace alignset::cli

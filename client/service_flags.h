#pragma once

#include <string>
#include <vector>

#include "client/args.h"
#include "client/service_client.h"

namespace alignset::cli {

// Flags shared by the subcommands that talk to a server:
//   --server ADDR       (default $ALIGNSET_SERVER, else 127.0.0.1:50051)
//   --tls-ca FILE       trust this root certificate and use TLS
//   --tls-server-name   name to check in the server's certificate
//   --token-file FILE   send its first line as the bearer token
//                       (default $ALIGNSET_TOKEN_FILE)
//   --timeout SECONDS   deadline of unary calls (default: none)
std::vector<std::string> ServiceFlags(std::vector<std::string> own);
StatusOr<ConnectOptions> ConnectOptionsFromArgs(const Args& args);
StatusOr<std::unique_ptr<ServiceClient>> ConnectFromArgs(const Args& args);

// "1024,4096" -> {1024, 4096}.
StatusOr<std::vector<uint32_t>> ParseCountList(const std::string& text, const std::string& what);

}  // namespace alignset::cli

#include "client/service_flags.h"

#include <cstdlib>
#include <fstream>
#include <sstream>

#include "core/optimize/optimizer.h"

namespace alignset::cli {

std::vector<std::string> ServiceFlags(std::vector<std::string> own) {
  for (const char* f : {"server", "tls-ca", "tls-server-name", "token-file", "timeout"}) own.push_back(f);
  return own;
}

StatusOr<ConnectOptions> ConnectOptionsFromArgs(const Args& args) {
  ConnectOptions o;
  const char* env_server = std::getenv("ALIGNSET_SERVER");
  auto server = args.String("server", env_server && *env_server ? env_server : kDefaultServerAddress);
  if (!server.ok()) return server.status();
  o.address = *server;
  auto ca = args.String("tls-ca", "");
  if (!ca.ok()) return ca.status();
  o.tls_ca_file = *ca;
  auto name = args.String("tls-server-name", "");
  if (!name.ok()) return name.status();
  o.tls_server_name = *name;
  const char* env_token = std::getenv("ALIGNSET_TOKEN_FILE");
  auto token_file = args.String("token-file", env_token ? env_token : "");
  if (!token_file.ok()) return token_file.status();
  if (!token_file->empty()) {
    std::ifstream in(*token_file);
    if (!in) return Status::InvalidArgument("cannot read --token-file " + *token_file);
    std::string line;
    std::getline(in, line);
    const auto b = line.find_first_not_of(" \t\r");
    const auto e = line.find_last_not_of(" \t\r");
    if (b == std::string::npos) return Status::InvalidArgument("--token-file " + *token_file + " holds no token");
    o.token = line.substr(b, e - b + 1);
  }
  auto timeout = args.Double("timeout", 0.0);
  if (!timeout.ok()) return timeout.status();
  if (*timeout < 0) return Status::InvalidArgument("--timeout must not be negative");
  o.timeout_seconds = *timeout;
  return o;
}

StatusOr<std::unique_ptr<ServiceClient>> ConnectFromArgs(const Args& args) {
  auto o = ConnectOptionsFromArgs(args);
  if (!o.ok()) return o.status();
  return ServiceClient::Connect(*o);
}

StatusOr<std::vector<uint32_t>> ParseCountList(const std::string& text, const std::string& what) {
  std::vector<uint32_t> out;
  std::stringstream ss(text);
  for (std::string item; std::getline(ss, item, ',');) {
    auto v = ParseInt(item, what, kMinPoints, kMaxPoints);
    if (!v.ok()) return v.status();
    out.push_back(static_cast<uint32_t>(*v));
  }
  if (out.empty()) return Status::InvalidArgument(what + ": empty list");
  return out;
}

}  // namespace alignset::cli

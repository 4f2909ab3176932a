// alignset-health-probe: asks a gRPC server's standard health service
// (grpc.health.v1.Health/Check) and exits 0 only when it answers SERVING.
// Used by the images' HEALTHCHECK and deploy/test-container.sh; Debian ships no
// grpc_health_probe.
//
// The two messages are tiny (HealthCheckRequest{string service = 1},
// HealthCheckResponse{ServingStatus status = 1}), so they are encoded by hand and sent
// through a generic stub: the probe then needs no generated code and builds from gRPC++
// alone.
#include <grpcpp/create_channel.h>
#include <grpcpp/generic/generic_stub.h>
#include <grpcpp/grpcpp.h>
#include <grpcpp/security/credentials.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

namespace {

constexpr int kExitServing = 0;
constexpr int kExitNotServing = 1;
constexpr int kExitUsage = 2;
constexpr int kExitUnreachable = 3;

const char* const kStatusNames[] = {"UNKNOWN", "SERVING", "NOT_SERVING", "SERVICE_UNKNOWN"};

void PutVarint(uint64_t v, std::string* out) {
  while (v >= 0x80) {
    out->push_back(static_cast<char>((v & 0x7f) | 0x80));
    v >>= 7;
  }
  out->push_back(static_cast<char>(v));
}

std::optional<uint64_t> GetVarint(const std::string& in, size_t* pos) {
  uint64_t v = 0;
  for (int shift = 0; shift < 64 && *pos < in.size(); shift += 7) {
    const auto byte = static_cast<uint8_t>(in[(*pos)++]);
    v |= static_cast<uint64_t>(byte & 0x7f) << shift;
    if ((byte & 0x80) == 0) return v;
  }
  return std::nullopt;
}

// HealthCheckResponse.status; a proto3 message without the field means UNKNOWN (0).
std::optional<uint64_t> ParseStatus(const std::string& msg) {
  uint64_t status = 0;
  size_t pos = 0;
  while (pos < msg.size()) {
    auto tag = GetVarint(msg, &pos);
    if (!tag) return std::nullopt;
    const uint64_t field = *tag >> 3, wire = *tag & 7;
    if (wire == 0) {
      auto v = GetVarint(msg, &pos);
      if (!v) return std::nullopt;
      if (field == 1) status = *v;
    } else if (wire == 1 || wire == 5) {
      pos += wire == 1 ? 8 : 4;
    } else if (wire == 2) {
      auto len = GetVarint(msg, &pos);
      if (!len || *len > msg.size() - std::min(pos, msg.size())) return std::nullopt;
      pos += *len;
    } else {
      return std::nullopt;
    }
  }
  if (pos != msg.size()) return std::nullopt;
  return status;
}

std::optional<std::string> ReadFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return std::nullopt;
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

int Usage(const char* msg) {
  if (msg != nullptr) std::fprintf(stderr, "alignset-health-probe: %s\n", msg);
  std::fprintf(stderr,
               "usage: alignset-health-probe [--server ADDR] [--service NAME] [--timeout S]\n"
               "                             [--tls] [--tls-ca FILE] [--tls-server-name NAME]\n"
               "  --server   default $ALIGNSET_SERVER or 127.0.0.1:50051\n"
               "  --service  health of one service (default \"\": the whole server)\n"
               "  --timeout  seconds (default 3)\n"
               "  --tls      TLS with the system roots; --tls-ca FILE: with this root\n"
               "exit status: 0 SERVING, 1 not serving, 2 usage, 3 unreachable\n");
  return kExitUsage;
}

}  // namespace

int main(int argc, char** argv) {
  const char* env_server = std::getenv("ALIGNSET_SERVER");
  std::string server = env_server != nullptr && *env_server != '\0' ? env_server : "127.0.0.1:50051";
  std::string service, tls_ca, tls_name;
  bool tls = false;
  double timeout = 3.0;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&]() -> const char* { return i + 1 < argc ? argv[++i] : nullptr; };
    if (a == "--help" || a == "-h") {
      Usage(nullptr);
      return 0;
    } else if (a == "--tls") {
      tls = true;
    } else if (a == "--server" || a == "--service" || a == "--timeout" || a == "--tls-ca" ||
               a == "--tls-server-name") {
      const char* v = value();
      if (v == nullptr) return Usage((a + " needs a value").c_str());
      if (a == "--server") server = v;
      if (a == "--service") service = v;
      if (a == "--tls-ca") tls_ca = v, tls = true;
      if (a == "--tls-server-name") tls_name = v;
      if (a == "--timeout") {
        char* end = nullptr;
        timeout = std::strtod(v, &end);
        if (*v == '\0' || *end != '\0' || !(timeout > 0 && timeout <= 3600)) {
          return Usage("--timeout must be seconds in (0, 3600]");
        }
      }
    } else {
      return Usage(("unknown argument " + a).c_str());
    }
  }

  std::shared_ptr<grpc::ChannelCredentials> creds = grpc::InsecureChannelCredentials();
  if (tls) {
    grpc::SslCredentialsOptions ssl;
    if (!tls_ca.empty()) {
      auto pem = ReadFile(tls_ca);
      if (!pem) return Usage(("cannot read --tls-ca " + tls_ca).c_str());
      ssl.pem_root_certs = *pem;
    }
    creds = grpc::SslCredentials(ssl);
  }
  grpc::ChannelArguments channel_args;
  if (!tls_name.empty()) channel_args.SetSslTargetNameOverride(tls_name);
  auto channel = grpc::CreateCustomChannel(server, creds, channel_args);

  std::string request;
  if (!service.empty()) {
    request.push_back(0x0a);  // field 1, length-delimited
    PutVarint(service.size(), &request);
    request += service;
  }
  grpc::Slice slice(request);
  grpc::ByteBuffer request_buffer(&slice, 1);

  grpc::GenericStub stub(channel);
  grpc::ClientContext ctx;
  ctx.set_deadline(std::chrono::system_clock::now() +
                   std::chrono::microseconds(static_cast<int64_t>(timeout * 1e6)));
  grpc::CompletionQueue cq;
  auto call = stub.PrepareUnaryCall(&ctx, "/grpc.health.v1.Health/Check", request_buffer, &cq);
  call->StartCall();
  grpc::ByteBuffer response_buffer;
  grpc::Status status;
  call->Finish(&response_buffer, &status, reinterpret_cast<void*>(1));
  void* tag = nullptr;
  bool ok = false;
  if (!cq.Next(&tag, &ok) || !ok) {
    std::fprintf(stderr, "alignset-health-probe: %s: call did not complete\n", server.c_str());
    return kExitUnreachable;
  }
  if (!status.ok()) {
    std::fprintf(stderr, "alignset-health-probe: %s: %s (gRPC code %d)\n", server.c_str(),
                 status.error_message().c_str(), static_cast<int>(status.error_code()));
    // NOT_FOUND is the health service's answer for an unknown --service.
    return status.error_code() == grpc::StatusCode::NOT_FOUND ? kExitNotServing
                                                              : kExitUnreachable;
  }
  std::vector<grpc::Slice> slices;
  std::string response;
  if (response_buffer.Dump(&slices).ok()) {
    for (const auto& s : slices) response.append(reinterpret_cast<const char*>(s.begin()), s.size());
  }
  auto serving = ParseStatus(response);
  if (!serving) {
    std::fprintf(stderr, "alignset-health-probe: %s: malformed health response\n", server.c_str());
    return kExitUnreachable;
  }
  const char* name = *serving < 4 ? kStatusNames[*serving] : "UNRECOGNIZED";
  std::printf("%s\n", name);
  return *serving == 1 ? kExitServing : kExitNotServing;
}

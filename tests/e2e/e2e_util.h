#pragma once

// Helpers shared by the end-to-end suites that talk to the server through
// raw gRPC stubs (so that they depend on the wire contract only, not on the
// client library's API).
#include <grpcpp/grpcpp.h>
#include <sys/types.h>

#include <map>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "alignset/v1/alignset.grpc.pb.h"

namespace alignset::e2e {

// A channel of its own (its own TCP connection, not one shared through
// gRPC's global subchannel pool): the server tells clients apart by their
// connection.
std::shared_ptr<grpc::Channel> OwnChannel(const std::string& address);
std::unique_ptr<v1::AlignSet::Stub> OwnStub(const std::string& address);

v1::AlignedSetRequest SetRequest(uint32_t n, std::vector<double> dirs);

// The server's metrics through GetMetrics (token: sent when not empty).
v1::MetricsResponse GetMetrics(const std::string& address, const std::string& token = "");

// TCP ports the process listens on (from /proc/PID/fd and /proc/net/tcp{,6}).
std::set<int> ListeningPorts(pid_t pid);

// "Threads:" and "VmRSS:" (kB) of /proc/PID/status; -1 when unreadable.
struct ProcessFigures {
  long threads = -1;
  long rss_kb = -1;
};
ProcessFigures ReadProcessFigures(pid_t pid);

// The whole file; empty when it cannot be read.
std::string ReadText(const std::string& path);

// Prometheus text exposition: sample name with labels ("name{a=\"b\"}")
// -> value, for every sample line.
std::map<std::string, double> ParsePrometheus(const std::string& text);

// Precomputes the 46 one-direction keys at N = 64 (fails the test unless
// all 46 are done).
void PrecomputeOneDirection(const std::string& address);

// One HTTP/1.0 request on a plain socket to 127.0.0.1:`port` (no curl
// needed on the test machine): the status code (0 when nothing came back),
// the header block and the body.
struct HttpReply {
  int status = 0;
  std::string headers;
  std::string body;
};
// `extra_headers`: more header lines, each ending in "\r\n".
HttpReply HttpRequest(int port, const std::string& method, const std::string& path,
                      const std::string& extra_headers = "");

}  // namespace alignset::e2e

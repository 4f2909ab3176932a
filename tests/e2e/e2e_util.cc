#include "tests/e2e/e2e_util.h"

#include <gtest/gtest.h>

#include <arpa/inet.h>
#include <dirent.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <sys/time.h>
#include <unistd.h>

#include <cstdlib>
#include <fstream>
#include <sstream>

namespace alignset::e2e {

std::shared_ptr<grpc::Channel> OwnChannel(const std::string& address) {
  grpc::ChannelArguments args;
  args.SetMaxSendMessageSize(-1);
  args.SetMaxReceiveMessageSize(-1);
  args.SetInt(GRPC_ARG_USE_LOCAL_SUBCHANNEL_POOL, 1);
  return grpc::CreateCustomChannel(address, grpc::InsecureChannelCredentials(), args);
}

std::unique_ptr<v1::AlignSet::Stub> OwnStub(const std::string& address) {
  return v1::AlignSet::NewStub(OwnChannel(address));
}

v1::AlignedSetRequest SetRequest(uint32_t n, std::vector<double> dirs) {
  v1::AlignedSetRequest req;
  req.set_n(n);
  for (double d : dirs) req.add_directions_deg(d);
  return req;
}

v1::MetricsResponse GetMetrics(const std::string& address, const std::string& token) {
  auto stub = OwnStub(address);
  grpc::ClientContext ctx;
  if (!token.empty()) ctx.AddMetadata("authorization", "Bearer " + token);
  ctx.set_deadline(std::chrono::system_clock::now() + std::chrono::seconds(10));
  v1::MetricsResponse resp;
  stub->GetMetrics(&ctx, v1::MetricsRequest(), &resp);
  return resp;
}

std::set<int> ListeningPorts(pid_t pid) {
  std::set<std::string> inodes;
  const std::string fd_dir = "/proc/" + std::to_string(pid) + "/fd";
  if (DIR* d = opendir(fd_dir.c_str())) {
    while (dirent* e = readdir(d)) {
      char target[256];
      const std::string link = fd_dir + "/" + e->d_name;
      const ssize_t len = readlink(link.c_str(), target, sizeof(target) - 1);
      if (len <= 0) continue;
      const std::string t(target, static_cast<size_t>(len));
      if (t.rfind("socket:[", 0) == 0) inodes.insert(t.substr(8, t.size() - 9));
    }
    closedir(d);
  }
  std::set<int> ports;
  for (const char* table : {"/proc/net/tcp", "/proc/net/tcp6"}) {
    std::ifstream in(table);
    std::string line;
    std::getline(in, line);  // header
    while (std::getline(in, line)) {
      std::istringstream fields(line);
      std::string slot, local, remote, state, queues, timer, retransmits, uid, timeout, inode;
      fields >> slot >> local >> remote >> state >> queues >> timer >> retransmits >> uid >> timeout >> inode;
      if (state != "0A" || inodes.count(inode) == 0) continue;  // 0A: LISTEN
      ports.insert(static_cast<int>(std::strtol(local.substr(local.rfind(':') + 1).c_str(), nullptr, 16)));
    }
  }
  return ports;
}

ProcessFigures ReadProcessFigures(pid_t pid) {
  ProcessFigures f;
  std::ifstream in("/proc/" + std::to_string(pid) + "/status");
  std::string key;
  while (in >> key) {
    if (key == "Threads:") in >> f.threads;
    if (key == "VmRSS:") in >> f.rss_kb;
    in.ignore(1 << 20, '\n');
  }
  return f;
}

// Precomputes the 46 one-direction keys at N = 64 (a few rows per 4 KiB
// page: the table spans several leaves).
void PrecomputeOneDirection(const std::string& address) {
  auto stub = OwnStub(address);
  grpc::ClientContext ctx;
  v1::PrecomputeRequest req;
  req.add_n(64);
  req.set_space(v1::ONE_DIRECTION);
  auto stream = stub->Precompute(&ctx, req);
  v1::PrecomputeProgress p;
  while (stream->Read(&p)) {
  }
  ASSERT_TRUE(stream->Finish().ok());
  ASSERT_EQ(p.done(), 46u);
}

std::string ReadText(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

std::map<std::string, double> ParsePrometheus(const std::string& text) {
  std::map<std::string, double> out;
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    const size_t space = line.rfind(' ');
    if (space == std::string::npos) continue;
    out[line.substr(0, space)] = std::strtod(line.c_str() + space + 1, nullptr);
  }
  return out;
}

HttpReply HttpRequest(int port, const std::string& method, const std::string& path,
                      const std::string& extra_headers) {
  HttpReply reply;
  const int fd = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
  if (fd < 0) return reply;
  timeval timeout{10, 0};
  ::setsockopt(fd, SOL_SOCKET, SO_RCVTIMEO, &timeout, sizeof(timeout));
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_port = htons(static_cast<uint16_t>(port));
  addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  std::string raw;
  if (::connect(fd, reinterpret_cast<sockaddr*>(&addr), sizeof(addr)) == 0) {
    const std::string request =
        method + " " + path + " HTTP/1.0\r\nHost: 127.0.0.1\r\n" + extra_headers + "\r\n";
    if (::send(fd, request.data(), request.size(), MSG_NOSIGNAL) == static_cast<ssize_t>(request.size())) {
      char buf[4096];
      for (ssize_t got; (got = ::recv(fd, buf, sizeof(buf), 0)) > 0;) raw.append(buf, static_cast<size_t>(got));
    }
  }
  ::close(fd);
  const size_t end = raw.find("\r\n\r\n");
  if (end == std::string::npos || raw.compare(0, 5, "HTTP/") != 0) return reply;
  reply.headers = raw.substr(0, end);
  reply.body = raw.substr(end + 4);
  const size_t space = reply.headers.find(' ');
  if (space != std::string::npos) reply.status = std::atoi(reply.headers.c_str() + space + 1);
  return reply;
}

}  // namespace alignset::e2e

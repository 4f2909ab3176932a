#pragma once

#include <sys/types.h>

#include <chrono>
#include <memory>
#include <string>
#include <vector>

#include <alignset/client.h>

namespace alignset::e2e {

// The server binary the tests start: the one built with them, or the one
// named by $ALIGNSET_E2E_SERVER (to run today's tests against an older build
// and see which of them it fails).
std::string ServerBinary();

// alignset-server as a child process: started on 127.0.0.1 with port 0 and a
// --port-file, so tests never race for a port. The destructor stops it with
// SIGTERM (or reaps it if a test killed it).
// The flags that give a server the default warm budget back (the harness
// starts servers with --warm-budget 0; see ServerProcess).
std::vector<std::string> DefaultWarmBudgetFlags();

class ServerProcess {
 public:
  // `dir` holds the database and the port file; `extra` are more flags.
  // The server starts with --warm-budget 0 (every key optimized from
  // Owen-Sobol, one optimization per key) unless `extra` sets it.
  ServerProcess(const std::string& dir, const std::vector<std::string>& extra);
  ~ServerProcess();
  ServerProcess(const ServerProcess&) = delete;
  ServerProcess& operator=(const ServerProcess&) = delete;

  // Empty when it came up; otherwise why not.
  const std::string& error() const { return error_; }
  std::string address() const { return "127.0.0.1:" + std::to_string(port_); }
  int port() const { return port_; }
  // The Prometheus port, when started with --metrics-listen; else 0.
  int metrics_port() const { return metrics_port_; }
  std::string log_path() const { return log_path_; }
  const std::string& db_path() const { return db_path_; }
  pid_t pid() const { return pid_; }

  // Sends `sig` and waits for the exit; returns the wait status.
  int Stop(int sig);
  // Waits, on the log file's write events, until `texts` have been logged
  // at least `count` times together (true) or `timeout` passes (false). The
  // server logs at warn unless a test passes --log-level.
  bool WaitForLog(const std::vector<std::string>& texts, int count, std::chrono::milliseconds timeout) const;

 private:
  std::string error_;
  std::string db_path_;
  pid_t pid_ = -1;
  int port_ = 0;
  int metrics_port_ = 0;
  std::string log_path_;
};

// A client-library connection to `server` with default options; a failure
// fails the calling test (and gives nullptr).
std::unique_ptr<ServiceClient> ConnectTo(const ServerProcess& server);

// A fresh directory under /tmp, removed by the destructor.
class TempDir {
 public:
  TempDir();
  ~TempDir();
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

// Runs a command line through /bin/sh; returns its exit status and output.
struct CommandResult {
  int exit_code = -1;
  std::string output;  // stdout and stderr together
};
CommandResult RunCommand(const std::string& command);

}  // namespace alignset::e2e

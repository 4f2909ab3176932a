#include "tests/e2e/server_process.h"

#include <gtest/gtest.h>
#include <signal.h>
#include <sys/inotify.h>
#include <stdlib.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <thread>

#include "core/optimize/optimizer.h"
#include "tests/e2e/file_events.h"

namespace alignset::e2e {

std::string ServerBinary() {
  const char* other = std::getenv("ALIGNSET_E2E_SERVER");
  return other != nullptr && *other != '\0' ? other : ALIGNSET_SERVER_PATH;
}

std::vector<std::string> DefaultWarmBudgetFlags() {
  return {"--warm-budget", std::to_string(OptimizerOptions{}.warm_budget_fraction)};
}

ServerProcess::ServerProcess(const std::string& dir, const std::vector<std::string>& extra) {
  db_path_ = dir + "/cache.sqlite";
  const std::string port_file = dir + "/port";
  std::filesystem::remove(port_file);
  std::vector<std::string> args = {ServerBinary(), "--listen", "127.0.0.1:0", "--port-file",
                                   port_file, "--db", db_path_, "--log-level", "warn",
                                   // Every key from Owen-Sobol unless a test asks for the key
                                   // lineage (a later --warm-budget in `extra` wins): most
                                   // suites count one optimization per requested key.
                                   "--warm-budget", "0"};
  args.insert(args.end(), extra.begin(), extra.end());
  const std::string log = dir + "/server.log";
  log_path_ = log;
  pid_ = fork();
  if (pid_ == 0) {
    FILE* f = std::fopen(log.c_str(), "a");
    if (f) {
      dup2(fileno(f), STDOUT_FILENO);
      dup2(fileno(f), STDERR_FILENO);
    }
    std::vector<char*> argv;
    for (auto& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    execv(argv[0], argv.data());
    _exit(127);
  }
  if (pid_ < 0) {
    error_ = "fork failed";
    return;
  }
  // The server renames its port file into place once it listens: that
  // event, or its exit, ends the wait (up to 30 s on a loaded machine).
  auto listening = [&] {
    std::ifstream in(port_file);
    if (!(in >> port_) || port_ <= 0) return false;
    std::string word;
    if (in >> word && word == "metrics") in >> metrics_port_;
    return true;
  };
  const WaitEnd end = WaitForFileEvent(dir, IN_MOVED_TO | IN_CLOSE_WRITE, pid_, listening, std::chrono::seconds(30));
  if (end == WaitEnd::kReady) return;
  if (end == WaitEnd::kExited) {
    int status = 0;
    waitpid(pid_, &status, 0);
    std::ifstream l(log);
    std::string text((std::istreambuf_iterator<char>(l)), std::istreambuf_iterator<char>());
    error_ = "alignset-server exited during start-up: " + text;
    pid_ = -1;
    return;
  }
  error_ = "alignset-server wrote no port file within 30 s";
}

bool ServerProcess::WaitForLog(const std::vector<std::string>& texts, int count,
                               std::chrono::milliseconds timeout) const {
  auto seen = [&] {
    std::ifstream in(log_path_);
    const std::string log((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    int found = 0;
    for (const std::string& text : texts) {
      for (size_t at = log.find(text); at != std::string::npos; at = log.find(text, at + 1)) ++found;
    }
    return found >= count;
  };
  return WaitForFileEvent(log_path_, IN_MODIFY, pid_, seen, timeout) == WaitEnd::kReady;
}

int ServerProcess::Stop(int sig) {
  if (pid_ <= 0) return -1;
  kill(pid_, sig);
  int status = 0;
  waitpid(pid_, &status, 0);
  pid_ = -1;
  return status;
}

ServerProcess::~ServerProcess() { Stop(SIGTERM); }

TempDir::TempDir() {
  char tmpl[] = "/tmp/alignset-e2e-XXXXXX";
  if (mkdtemp(tmpl)) path_ = tmpl;
}

TempDir::~TempDir() {
  std::error_code ec;
  if (!path_.empty()) std::filesystem::remove_all(path_, ec);
}

CommandResult RunCommand(const std::string& command) {
  CommandResult r;
  FILE* p = popen((command + " 2>&1").c_str(), "r");
  if (!p) return r;
  char buf[4096];
  size_t got;
  while ((got = std::fread(buf, 1, sizeof(buf), p)) > 0) r.output.append(buf, got);
  const int status = pclose(p);
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

std::unique_ptr<ServiceClient> ConnectTo(const ServerProcess& server) {
  ConnectOptions o;
  o.address = server.address();
  auto c = ServiceClient::Connect(o);
  EXPECT_TRUE(c.ok()) << c.status().message();
  return c.ok() ? std::move(c).value() : nullptr;
}

}  // namespace alignset::e2e

// alignset-server's command line (issue 15): --help and --version on stdout
// with status 0, usage errors with status 2, the ALIGNSET_<FLAG> environment
// fallbacks, and the profile --version names is the one a default server uses.
#include <gtest/gtest.h>
#include <stdlib.h>

#include <algorithm>
#include <string>

#include <alignset/client.h>
#include "storage/set_cache.h"
#include "tests/e2e/server_process.h"

namespace alignset::e2e {
namespace {

const std::string kServer = ALIGNSET_SERVER_PATH;

int Lines(const std::string& s) { return static_cast<int>(std::count(s.begin(), s.end(), '\n')); }

TEST(ServerCli, HelpListsEveryFlagWithItsVariableOnStdout) {
  for (const char* flag : {"--help", "-h"}) {
    // stdout only: stderr goes to /dev/null.
    const CommandResult r = RunCommand(kServer + " " + flag + " 2>/dev/null");
    EXPECT_EQ(r.exit_code, 0) << r.output;
    for (const char* f : {"--listen", "--db", "--workers", "--threads-per-worker", "--max-n",
                          "--max-iterations", "--engine", "--seed", "--max-queue",
                          "--memory-cache-mb", "--lattice-terms-mb", "--max-request-bytes", "--tls-cert", "--tls-key",
                          "--token-file", "--port-file", "--log-level", "--shutdown-grace",
                          "--version"}) {
      EXPECT_NE(r.output.find(f), std::string::npos) << f;
    }
    for (const char* env : {"ALIGNSET_LISTEN", "ALIGNSET_DB", "ALIGNSET_MAX_N", "ALIGNSET_WORKERS",
                            "ALIGNSET_THREADS_PER_WORKER", "ALIGNSET_TOKEN_FILE"}) {
      EXPECT_NE(r.output.find(env), std::string::npos) << env;
    }
    EXPECT_NE(r.output.find("Exit status: 0"), std::string::npos);
  }
}

TEST(ServerCli, VersionNamesReleaseAlgorithmVersionAndProfile) {
  for (const char* flag : {"--version", "-V"}) {
    const CommandResult r = RunCommand(kServer + " --workers 2 " + flag + " 2>/dev/null");
    EXPECT_EQ(r.exit_code, 0) << r.output;
    EXPECT_EQ(r.output.rfind(std::string("alignset-server ") + ALIGNSET_VERSION + "\n", 0), 0u)
        << r.output;
    EXPECT_NE(r.output.find("algorithm version " + std::to_string(storage::kAlgorithmVersion)),
              std::string::npos);
    EXPECT_NE(r.output.find("profile "), std::string::npos);
  }
}

TEST(ServerCli, UsageErrorsExitTwoWithOneLine) {
  for (const std::string& args :
       {std::string("--bogus 1"), std::string("--workers 0"), std::string("--max-n 8"),
        std::string("--engine warp"), std::string("--tls-cert a.pem"),
        std::string("stray-argument")}) {
    const CommandResult r = RunCommand(kServer + " " + args);
    EXPECT_EQ(r.exit_code, 2) << args << ": " << r.output;
    EXPECT_EQ(Lines(r.output), 1) << args << ": " << r.output;
    EXPECT_EQ(r.output.rfind("alignset-server: ", 0), 0u) << r.output;
  }
  // A bad environment value is a usage error too, naming the variable.
  const CommandResult env = RunCommand("ALIGNSET_WORKERS=zero " + kServer);
  EXPECT_EQ(env.exit_code, 2) << env.output;
  EXPECT_NE(env.output.find("ALIGNSET_WORKERS"), std::string::npos) << env.output;
}

TEST(ServerCli, EnvironmentVariablesConfigureAndFlagsWin) {
  TempDir dir;
  // The child inherits the environment: ALIGNSET_MAX_N sets the limit...
  setenv("ALIGNSET_MAX_N", "1024", 1);
  setenv("ALIGNSET_MAX_ITERATIONS", "30", 1);
  {
    ServerProcess server(dir.path(), {"--workers", "1", "--threads-per-worker", "1"});
    ASSERT_EQ(server.error(), "");
    ConnectOptions o;
    o.address = server.address();
    auto client = ServiceClient::Connect(o);
    ASSERT_TRUE(client.ok());
    auto over = (*client)->GetAlignedSet(2048, {30.0});
    ASSERT_FALSE(over.ok());
    EXPECT_NE(over.status().message().find("maximum of 1024"), std::string::npos)
        << over.status().message();
    auto set = (*client)->GetAlignedSet(64, {30.0});
    ASSERT_TRUE(set.ok()) << set.status().message();
    EXPECT_EQ(set->info.max_iterations, 30);
  }
  // ...and a flag wins over its variable.
  {
    ServerProcess server(dir.path(), {"--max-n", "4096", "--workers", "1"});
    ASSERT_EQ(server.error(), "");
    ConnectOptions o;
    o.address = server.address();
    auto client = ServiceClient::Connect(o);
    ASSERT_TRUE(client.ok());
    auto set = (*client)->GetAlignedSet(2048, {30.0});
    ASSERT_TRUE(set.ok()) << set.status().message();
  }
  unsetenv("ALIGNSET_MAX_N");
  unsetenv("ALIGNSET_MAX_ITERATIONS");
}

TEST(ServerCli, TheCliVersionNamesTheProfileOfADefaultServer) {
  TempDir dir;
  ServerProcess server(dir.path(), DefaultWarmBudgetFlags());
  ASSERT_EQ(server.error(), "");
  ConnectOptions o;
  o.address = server.address();
  auto client = ServiceClient::Connect(o);
  ASSERT_TRUE(client.ok());
  auto stats = (*client)->GetCacheStats();
  ASSERT_TRUE(stats.ok()) << stats.status().message();
  ASSERT_FALSE(stats->profile_hint.empty());
  for (const std::string& bin : {kServer, std::string(ALIGNSET_CLI_PATH)}) {
    const CommandResult v = RunCommand(bin + " --version");
    EXPECT_NE(v.output.find("profile " + stats->profile_hint + " "), std::string::npos)
        << bin << ": " << v.output << " vs " << stats->profile_hint;
  }
}

}  // namespace
}  // namespace alignset::e2e

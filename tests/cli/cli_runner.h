#pragma once

// Runs the real `alignset` binary the way a user would, for the CLI tests.

#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

namespace alignset::test_support {

struct CliRun {
  int exit_code;
  std::string out;  // standard output
  std::string err;  // standard error
};

// A per-process path in the test temp directory.
inline std::string CliTempPath(const std::string& name) {
  return ::testing::TempDir() + "/alignset_cli_" + std::to_string(getpid()) + "_" + name;
}

inline CliRun RunCli(const std::string& args) {
  const std::string err_path = CliTempPath("stderr.txt");
  const std::string cmd = std::string(ALIGNSET_CLI_PATH) + " " + args + " 2>" + err_path;
  CliRun run{-1, "", ""};
  if (FILE* p = popen(cmd.c_str(), "r")) {
    char buf[512];
    while (std::fgets(buf, sizeof(buf), p)) run.out += buf;
    const int status = pclose(p);
    run.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  }
  std::ifstream in(err_path);
  std::stringstream ss;
  ss << in.rdbuf();
  run.err = ss.str();
  return run;
}

inline int CountLines(const std::string& s) {
  int n = 0;
  for (char c : s) n += c == '\n';
  return n;
}

}  // namespace alignset::test_support

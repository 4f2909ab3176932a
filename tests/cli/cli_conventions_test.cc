// The command line's conventions (issue 15): help on stdout with status 0 for
// every command, --version, UTK's short options, and the documented exit
// statuses (0 ok, 1 failure, 2 usage), through the real binary.
#include <gtest/gtest.h>

#include <cstdio>
#include <string>
#include <vector>

#include "cli/point_file.h"
#include "core/sampling/samplers.h"
#include "core/spectral/frequency_set.h"
#ifdef ALIGNSET_HAVE_STORAGE
#include "storage/set_cache.h"
#endif
#include "tests/cli/cli_runner.h"

namespace alignset::cli {
namespace {

using test_support::CliRun;
using test_support::RunCli;

std::string TempPath(const std::string& name) { return test_support::CliTempPath(name); }

// Every command and subcommand the binary has.
std::vector<std::string> AllCommands() {
  std::vector<std::string> c = {"",         "optimize", "evaluate", "sample",    "align",
                                "variance", "analyze",  "convergence", "direction"};
#ifdef ALIGNSET_HAVE_STORAGE
  for (const char* s : {"cache", "cache export", "cache import", "cache merge", "cache verify",
                        "cache list"}) {
    c.push_back(s);
  }
#endif
#ifdef ALIGNSET_HAVE_SERVICE
  for (const char* s : {"get", "precompute", "stats"}) c.push_back(s);
#endif
  return c;
}

TEST(CliConventions, EveryCommandAnswersHelpOnStdoutWithStatusZero) {
  for (const std::string& cmd : AllCommands()) {
    for (const char* flag : {"--help", "-h"}) {
      const CliRun r = RunCli(cmd + " " + flag);
      EXPECT_EQ(r.exit_code, 0) << cmd << " " << flag << ": " << r.err;
      EXPECT_EQ(r.err, "") << cmd;
      const std::string usage = "Usage: alignset" + (cmd.empty() ? "" : " " + cmd);
      EXPECT_NE(r.out.find(usage), std::string::npos) << cmd << ":\n" << r.out;
      // The exit statuses are documented on every page.
      EXPECT_NE(r.out.find("Exit status: 0"), std::string::npos) << cmd;
      EXPECT_NE(r.out.find("2 usage"), std::string::npos) << cmd;
    }
  }
  // The word `help` where a command is expected asks for that level's help.
  std::vector<std::string> groups = {"help"};
#ifdef ALIGNSET_HAVE_STORAGE
  groups.push_back("cache help");
#endif
  for (const std::string& cmd : groups) {    const CliRun r = RunCli(cmd);
    EXPECT_EQ(r.exit_code, 0) << cmd;
    EXPECT_NE(r.out.find("Subcommands:"), std::string::npos) << r.out;
  }
  // The top-level page names every command.
  const CliRun top = RunCli("--help");
  for (const std::string& cmd : AllCommands()) {
    if (cmd.empty() || cmd.find(' ') != std::string::npos) continue;
    EXPECT_NE(top.out.find("\n  " + cmd + " "), std::string::npos) << cmd;
  }
}

// Every command that takes --construction describes each name it accepts in
// its help, not only in the list of allowed values (get and precompute once
// accepted tent-lattice without a word on what it is).
TEST(CliConventions, ConstructionHelpDescribesEveryAcceptedName) {
  std::vector<std::string> commands = {"optimize"};
#ifdef ALIGNSET_HAVE_SERVICE
  commands.push_back("get");
  commands.push_back("precompute");
#endif
  for (const std::string& cmd : commands) {
    const CliRun r = RunCli(cmd + " --help");
    ASSERT_EQ(r.exit_code, 0) << cmd;
    // The help wraps its descriptions into a column: read it as one line.
    std::string text;
    for (char c : r.out) {
      const bool space = c == ' ' || c == '\n';
      if (!(space && !text.empty() && text.back() == ' ')) text.push_back(space ? ' ' : c);
    }
    for (const char* name : {" optimized (", " lattice (", " tent-lattice (", " net ("}) {
      EXPECT_NE(text.find(name), std::string::npos)
          << cmd << " --help does not describe '" << name << "':\n" << r.out;
    }
  }
}

#ifdef ALIGNSET_HAVE_STORAGE
TEST(CliConventions, VersionNamesReleaseAlgorithmVersionAndProfile) {
  for (const char* flag : {"--version", "-V"}) {
    const CliRun r = RunCli(flag);
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(r.err, "");
    EXPECT_NE(r.out.find(std::string("alignset ") + ALIGNSET_VERSION + "\n"), std::string::npos)
        << r.out;
    EXPECT_NE(r.out.find("algorithm version " + std::to_string(storage::kAlgorithmVersion) + "\n"),
              std::string::npos)
        << r.out;
    // The id a default server caches N = 4096 sets under.
    const std::string profile =
        storage::ProfileId(DefaultFrequencyParams(4096), OptimizerOptions{}, 1);
    EXPECT_NE(r.out.find("profile " + profile), std::string::npos) << r.out;
  }
}
#endif

TEST(CliConventions, UtkShortOptionsMeanTheLongOnes) {
  const std::string a = TempPath("short.dat"), b = TempPath("long.dat");
  // The example: a .dat name is UTK text.
  CliRun r = RunCli("sample random -n 64 -s 3 -o " + a);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(*ReadPointFile(a), *Sample("random", 64, 3));
  r = RunCli("optimize -n 64 --dir 30 -s 2 --max-iterations 20 -o " + a);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  r = RunCli("optimize --n 64 --dir 30 --seed 2 --max-iterations 20 --out " + b);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(*ReadPointFile(a), *ReadPointFile(b));
  // Seeds are unsigned 64-bit: a realization's seed (above INT64_MAX) can be given back.
  r = RunCli("sample random -n 16 -s 18446744073709551615 -o " + a);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(*ReadPointFile(a), *Sample("random", 16, UINT64_MAX));
  r = RunCli("variance " + a + " --normal 30 -s 5 --shifts 64");
  const CliRun l = RunCli("variance " + a + " --normal 30 --seed 5 --shifts 64");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out, l.out);
  std::remove(a.c_str());
  std::remove(b.c_str());
}

TEST(CliConventions, UsageErrorsExitTwoWithOneLineNamingTheCommand) {
  const std::string out = TempPath("usage.txt");
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"", "alignset: name a command"},
      {"frobnicate", "alignset: unknown command 'frobnicate'"},
      {"optimize --n 64 --dir 30", "alignset optimize: --out is required"},
      {"optimize -n 64 --dir 30 -s -1 -o " + out, "alignset optimize: --seed"},
      {"optimize --n 64 --dir 30 --bogus 1 -o " + out, "alignset optimize: unexpected argument(s): --bogus 1"},
      {"evaluate --normal 30", "alignset evaluate: FILE is required"},
      {"evaluate /nonexistent.txt --normal 30", "alignset evaluate: cannot read"},
      {"sample random -n abc -o " + out, "alignset sample: --n: 'abc' is not an integer"},
      {"align --canonical 30 --dir 120 -o " + out, "alignset align:"},
      {"variance /nonexistent.txt --normal 30", "alignset variance:"},
#ifdef ALIGNSET_HAVE_STORAGE
      {"cache", "alignset cache: name a command"},
      {"cache frob", "alignset cache: unknown command 'frob'"},
      {"cache verify", "alignset cache verify: --db is required"},
#endif
#ifdef ALIGNSET_HAVE_SERVICE
      {"get --dir 30 -o " + out, "alignset get: --n is required"},
      {"get -n 64 --dir 30 --dir 40 --dir 50 -o " + out, "alignset get: give one or two"},
      {"get -n 64 --dir 30 -o " + out + " --token-file /nonexistent", "alignset get: cannot read"},
      {"precompute --n 8", "alignset precompute: --n: N = 8 is below the minimum of 16 points"},
      {"precompute --n 64 --shard 3", "alignset precompute: --shard"},
      {"precompute --n 64 --space 3dir", "alignset precompute: --space"},
      {"stats --limit -1", "alignset stats: --limit"},
#endif
  };
  for (const auto& [args, message] : cases) {
    const CliRun r = RunCli(args);
    EXPECT_EQ(r.exit_code, 2) << args << ": " << r.err;
    EXPECT_EQ(test_support::CountLines(r.err), 1) << args << ": " << r.err;
    EXPECT_EQ(r.err.rfind(message, 0), 0u) << args << ": " << r.err;
    EXPECT_EQ(r.out, "") << args;
  }
}

TEST(CliConventions, FailuresOfTheWorkExitOne) {
  CliRun r = RunCli("optimize --n 64 --dir 30 --out /nonexistent-dir/set.txt");
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_EQ(r.err.rfind("alignset optimize: cannot write", 0), 0u) << r.err;
  r = RunCli("sample random -n 16 -o /nonexistent-dir/set.txt");
  EXPECT_EQ(r.exit_code, 1) << r.err;
#ifdef ALIGNSET_HAVE_SERVICE
  // Nothing listens on port 1: the server cannot be reached.
  r = RunCli("get -n 64 --dir 30 -o " + TempPath("down.txt") + " --server 127.0.0.1:1");
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_EQ(test_support::CountLines(r.err), 1) << r.err;
  EXPECT_NE(r.err.find("UNAVAILABLE"), std::string::npos) << r.err;
#endif
}

}  // namespace
}  // namespace alignset::cli

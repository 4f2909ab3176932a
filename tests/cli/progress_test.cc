// The progress bar fits the terminal (issue 15): the layout at every width,
// and the real binary drawing on a pseudo-terminal of a known size.
#include <gtest/gtest.h>

#include <fcntl.h>
#include <pty.h>
#include <sys/ioctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "cli/progress.h"
#include "tests/cli/cli_runner.h"

namespace alignset::cli {
namespace {

const std::string kLongDetail =
    "loss 0.0123456 (spec 0.00123 sw 1.23e-05) lr 0.00021 reverts 3 and some more words";

TEST(ProgressBar, EveryWidthGetsALineThatFits) {
  for (int columns = 1; columns <= 200; ++columns) {
    for (double f : {0.0, 0.37, 1.0}) {
      const std::string line = BarLine(columns, "optimize", f, 65.0, 3700.0, kLongDetail);
      EXPECT_LE(static_cast<int>(line.size()), columns - 1) << columns << ": '" << line << "'";
    }
  }
  // Wide: the whole bar (30 cells), the percentage, the times and the detail.
  const std::string wide = BarLine(200, "optimize", 0.5, 65.0, 65.0, kLongDetail);
  EXPECT_NE(wide.find("[" + std::string(15, '#') + std::string(15, '.') + "]"), std::string::npos)
      << wide;
  EXPECT_NE(wide.find(" 50% 01:05<01:05 " + kLongDetail), std::string::npos) << wide;
  // 80 columns: the bar stays, the detail is cut to fit.
  const std::string eighty = BarLine(80, "optimize", 0.5, 65.0, 65.0, kLongDetail);
  EXPECT_EQ(eighty.size(), 79u);
  EXPECT_NE(eighty.find("]  50% 01:05<01:05 loss"), std::string::npos) << eighty;
  // Narrow: no bar, but the percentage is still there.
  const std::string narrow = BarLine(24, "optimize", 0.5, 65.0, 65.0, kLongDetail);
  EXPECT_EQ(narrow.find('['), std::string::npos) << narrow;
  EXPECT_NE(narrow.find("50%"), std::string::npos) << narrow;
}

struct PtyRun {
  int exit_code = -1;
  std::string screen;  // everything written to the terminal
};

// Runs the CLI with its stderr on a fresh pseudo-terminal of `columns`
// columns (0: a terminal that reports no size) and `env_columns` as COLUMNS.
PtyRun RunOnPty(const std::string& args, int columns, const char* env_columns) {
  PtyRun run;
  int master = -1, slave = -1;
  winsize ws{};
  ws.ws_row = 24;
  ws.ws_col = static_cast<unsigned short>(columns);
  if (openpty(&master, &slave, nullptr, nullptr, &ws) != 0) {
    ADD_FAILURE() << "openpty: " << std::strerror(errno);
    return run;
  }
  const pid_t pid = fork();
  if (pid == 0) {
    close(master);
    dup2(slave, STDERR_FILENO);
    const int null = open("/dev/null", O_WRONLY);
    dup2(null, STDOUT_FILENO);
    if (env_columns) {
      setenv("COLUMNS", env_columns, 1);
    } else {
      unsetenv("COLUMNS");
    }
    const std::string cmd = std::string(ALIGNSET_CLI_PATH) + " " + args;
    execl("/bin/sh", "sh", "-c", cmd.c_str(), static_cast<char*>(nullptr));
    _exit(127);
  }
  close(slave);
  char buf[4096];
  for (;;) {
    const ssize_t got = read(master, buf, sizeof(buf));
    if (got > 0) {
      run.screen.append(buf, static_cast<size_t>(got));
    } else if (got < 0 && errno == EINTR) {
      continue;
    } else {
      break;  // EIO once the child has closed the terminal
    }
  }
  close(master);
  int status = 0;
  waitpid(pid, &status, 0);
  run.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return run;
}

// The redraws as the terminal shows them: split at \r and \n, without the
// erase-to-end-of-line sequence.
std::vector<std::string> Redraws(std::string screen) {
  for (size_t p; (p = screen.find("\x1b[K")) != std::string::npos;) screen.erase(p, 3);
  std::vector<std::string> out;
  std::string cur;
  for (char c : screen) {
    if (c == '\r' || c == '\n') {
      if (!cur.empty()) out.push_back(cur);
      cur.clear();
    } else {
      cur += c;
    }
  }
  if (!cur.empty()) out.push_back(cur);
  return out;
}

void ExpectBarFits(int columns, const char* env_columns, int expected_width) {
  const std::string out = test_support::CliTempPath("pty.txt");
  const PtyRun r = RunOnPty("optimize -n 256 --dir 30 --max-iterations 200 --threads 1 -o " + out,
                            columns, env_columns);
  ASSERT_EQ(r.exit_code, 0) << r.screen;
  const std::vector<std::string> lines = Redraws(r.screen);
  int bars = 0;
  for (const std::string& l : lines) {
    EXPECT_LT(static_cast<int>(l.size()), expected_width) << "'" << l << "'";
    bars += l.find("% ") != std::string::npos;
  }
  EXPECT_GE(bars, 10) << r.screen;  // it did redraw (every 10 of 200 iterations)
  std::remove(out.c_str());
}

TEST(ProgressBar, FitsThePseudoTerminalsOwnWidth) {
  // The terminal's size wins over a COLUMNS that says otherwise.
  ExpectBarFits(50, "200", 50);
  ExpectBarFits(120, nullptr, 120);
}

TEST(ProgressBar, FallsBackToColumnsWhenTheTerminalHasNoSize) {
  ExpectBarFits(0, "40", 40);
}

}  // namespace
}  // namespace alignset::cli

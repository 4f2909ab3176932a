#include "cli/plot_script.h"

#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <vector>

namespace alignset::cli {
namespace {

namespace fs = std::filesystem;

std::string Env(const char* name) {
  const char* v = std::getenv(name);
  return v ? v : "";
}

}  // namespace

StatusOr<std::string> FindPlotScript() {
  std::vector<fs::path> candidates;
  if (std::string e = Env("ALIGNSET_PLOT_SCRIPT"); !e.empty()) {
    if (!fs::is_regular_file(e)) {
      return Status::NotFound("ALIGNSET_PLOT_SCRIPT=" + e + " is not a file");
    }
    return e;
  }
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) candidates.push_back(exe.parent_path().parent_path() / "share/alignset/plot_analysis.py");
#ifdef ALIGNSET_SOURCE_DIR_FOR_SCRIPTS
  candidates.push_back(fs::path(ALIGNSET_SOURCE_DIR_FOR_SCRIPTS) / "scripts/plot_analysis.py");
#endif
  for (const fs::path& p : candidates) {
    if (fs::is_regular_file(p, ec)) return p.string();
  }
  return Status::NotFound(
      "cannot find plot_analysis.py (set ALIGNSET_PLOT_SCRIPT to scripts/plot_analysis.py)");
}

Status WritePlot(const std::string& json, const std::string& png) {
  auto script = FindPlotScript();
  if (!script.ok()) return script.status();
  std::string python = Env("ALIGNSET_PYTHON");
  if (python.empty()) python = "/usr/bin/python3";

  char tmp[] = "/tmp/alignset-plot-XXXXXX";
  const int fd = mkstemp(tmp);
  if (fd < 0) return Status::Unavailable("cannot create a temporary file for the plot data");
  close(fd);
  {
    std::ofstream out(tmp, std::ios::binary);
    out << json;
    if (!out) {
      std::remove(tmp);
      return Status::Unavailable(std::string("cannot write ") + tmp);
    }
  }
  std::fflush(stdout);
  std::fflush(stderr);
  const pid_t pid = fork();
  if (pid < 0) {
    std::remove(tmp);
    return Status::Unavailable("cannot start " + python);
  }
  if (pid == 0) {
    std::vector<char*> argv = {python.data(), script->data(), tmp, const_cast<char*>("--out"),
                               const_cast<char*>(png.c_str()), nullptr};
    execv(python.c_str(), argv.data());
    std::fprintf(stderr, "cannot run %s\n", python.c_str());
    _exit(127);
  }
  int status = 0;
  while (waitpid(pid, &status, 0) < 0) {
  }
  std::remove(tmp);
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    return Status::Unavailable("plotting failed: " + python + " " + *script + " (exit status " +
                               std::to_string(WIFEXITED(status) ? WEXITSTATUS(status) : -1) +
                               "); the numbers are still available with --json");
  }
  return Status::Ok();
}

}  // namespace alignset::cli

// The `alignset` command line on any bytes: NUL-separated arguments to the
// whole command (every subcommand, CLI11 with the project's validators),
// parsed by RunApp in parse-only mode (cli::ParseOnlyForFuzzing: a command
// whose line parsed is marked, not run). Exit 0 (a command chosen, or help or the
// version asked for) or 2 (a usage error, one line); never another status,
// an exception or a crash.
#include <cstdint>
#include <cstdlib>
#include <string>
#include <vector>

#include "cli/app_commands.h"
#include "fuzz/fuzz_args.h"

namespace {

bool AsksForHelpOrVersion(const std::vector<std::string>& args) {
  for (const std::string& a : args) {
    if (a == "help" || a == "-h" || a == "--help" || a == "--help-all" || a == "-V" || a == "--version") return true;
    // CLI11 takes short flags together ("-hx") and "--help=..." as the flag.
    if (a.size() > 1 && a[0] == '-' && a[1] != '-' && (a.find('h') != std::string::npos || a.find('V') != std::string::npos)) {
      return true;
    }
    if (a.rfind("--help", 0) == 0 || a.rfind("--version", 0) == 0) return true;
  }
  return false;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  alignset::fuzz::FuzzArgs line("alignset", data, size);
  const std::vector<std::string>& args = line.args;

  CLI::App app;
  alignset::cli::AddEveryCommand(app);
  bool ran = false;
  alignset::cli::ParseOnlyForFuzzing(&ran);
  const int rc = alignset::cli::RunApp(app, line.argc(), line.argv.data());
  if (rc != alignset::cli::kExitOk && rc != alignset::cli::kExitUsage) std::abort();
  // Success means a command was chosen (its marker ran) or help/the version
  // was printed; a usage error runs nothing.
  if (rc == alignset::cli::kExitOk && !ran && !AsksForHelpOrVersion(args)) std::abort();
  if (rc == alignset::cli::kExitUsage && ran) std::abort();
  return 0;
}

#pragma once

// The whole `alignset` command line on one CLI::App: every subcommand this
// build has. main.cc runs it; the command-line fuzzer (fuzz/) parses it.

#include "cli/cli_app.h"

namespace alignset::cli {

// The top-level description, --version and the exit-status footer, then
// every subcommand (render only where the renderer library is built).
void AddEveryCommand(CLI::App& app);

}  // namespace alignset::cli

#pragma once

// The plumbing every `alignset` subcommand shares: exit statuses, the one-line
// error style, checked number validators, and the parse-and-run entry point.
// The parser is CLI11 (Debian's libcli11-dev, the parser UTK uses).

#include <CLI/CLI.hpp>

#include <cstdint>
#include <functional>
#include <string>

#include "core/util/status.h"

namespace alignset::cli {

// Exit statuses, the same for every subcommand (and in every --help footer):
//   0  success;
//   1  failure: the work did not succeed (the server refused or could not be
//      reached, an output could not be written, damaged sets were found);
//   2  usage: the command line is wrong (unknown command or option, a missing
//      or malformed value, flags that do not go together) or an input it names
//      is missing or holds something other than what the command reads.
inline constexpr int kExitOk = 0;
inline constexpr int kExitFailure = 1;
inline constexpr int kExitUsage = 2;

// The footer of every help page.
extern const char kExitStatusHelp[];

// Prints `s` as the one error line "alignset <command>: <message>" on stderr
// and returns `exit_code`.
int ReportError(const std::string& command, const Status& s, int exit_code);

// Ends a subcommand's callback with `exit_code` (RunApp returns it).
void Finish(int exit_code);

// Validators whose messages are those of core/util/number_text.h, so the
// command line and the server's configuration refuse a value in the same words:
// an integer in [lo, hi]; a finite real number (no nan, inf, overflow); a
// finite number in [lo, hi].
CLI::Validator IntegerIn(int64_t lo, int64_t hi);
// A seed: any unsigned 64-bit integer (the server reports realization seeds
// beyond INT64_MAX, and `optimize --seed` must reproduce them).
CLI::Validator SeedValue();
CLI::Validator FiniteNumber();
CLI::Validator FiniteIn(double lo, double hi);
// The constructions a set can be made by, in the server's words
// (server/construction.h): optimized, lattice, tent-lattice, net. One list, so
// that get, precompute and optimize accept the same names.
CLI::Validator ConstructionName();
// A point count N: an integer refused in the words of the one rule for N
// (core/optimize/point_count.h) that the server, the cache and a table file
// use too. A construction's own size rule is checked where the construction
// is known (ValidatePointCount(n, construction)).
CLI::Validator PointCount();

// A subcommand of `parent`; it inherits the parent's footer (the exit
// statuses), so set that first.
CLI::App* AddCommand(CLI::App& parent, const std::string& name, const std::string& description);

// `run` is what `command` does once its command line parsed: its exit status
// ends the program (Finish). `run` owns the options the command's flags were
// parsed into.
void OnRun(CLI::App* command, std::function<int()> run);

// Parse only, for the command-line fuzzer (fuzz/): from now on a command
// whose command line parsed sets *ran instead of running; null runs again.
void ParseOnlyForFuzzing(bool* ran);

// Parses argv and runs the chosen subcommand's callback. Help (--help, -h, or
// the word `help` where a command is expected) and --version go to stdout
// with status 0; a usage error is one line on stderr with status 2.
int RunApp(CLI::App& app, int argc, char** argv);

}  // namespace alignset::cli

#include "cli/cli_app.h"

#include <algorithm>
#include <charconv>
#include <cstdio>
#include <iostream>
#include <vector>

#include "core/optimize/construction.h"
#include "core/optimize/point_count.h"
#include "core/util/number_text.h"

namespace alignset::cli {
namespace {

// core/util/number_text.h names the value first ("--n: 'x' is not an
// integer"); CLI11 prefixes the option's name itself.
std::string WithoutSubject(const std::string& message) {
  const auto colon = message.find(": ");
  return colon == std::string::npos ? message : message.substr(colon + 2);
}

std::string CommandList(const CLI::App& app) {
  std::string names;
  for (const CLI::App* sub : app.get_subcommands([](const CLI::App*) { return true; })) {
    names += (names.empty() ? "" : ", ") + sub->get_name();
  }
  return names;
}

std::string Prefixed(const std::string& path) { return path.empty() ? "" : " " + path; }

}  // namespace

const char kExitStatusHelp[] =
    "Exit status: 0 success; 1 failure (the server refused or could not be reached, an output\n"
    "could not be written, damaged sets were found); 2 usage (a wrong command line, or an input\n"
    "file that is missing or not what the command reads).";

int ReportError(const std::string& command, const Status& s, int exit_code) {
  std::fprintf(stderr, "alignset%s: %s\n", Prefixed(command).c_str(), s.message().c_str());
  return exit_code;
}

void Finish(int exit_code) {
  // CLI11's way out of a callback with a status: RunApp catches it.
  if (exit_code != kExitOk) throw CLI::RuntimeError(exit_code);
}

CLI::Validator IntegerIn(int64_t lo, int64_t hi) {
  return CLI::Validator(
      [lo, hi](std::string& text) {
        auto v = ParseInt(text, "", lo, hi);
        return v.ok() ? std::string() : WithoutSubject(v.status().message());
      },
      "", "integer in range");
}

CLI::Validator SeedValue() {
  return CLI::Validator(
      [](std::string& text) {
        uint64_t v = 0;
        const char* end = text.data() + text.size();
        const auto r = std::from_chars(text.data(), end, v);
        if (text.empty() || r.ec == std::errc::invalid_argument || r.ptr != end) {
          return "'" + text + "' is not a seed (an integer in [0, 18446744073709551615])";
        }
        if (r.ec == std::errc::result_out_of_range) return text + " is above 18446744073709551615";
        return std::string();
      },
      "", "seed");
}

CLI::Validator FiniteNumber() {
  return CLI::Validator(
      [](std::string& text) {
        auto v = ParseFiniteDouble(text, "");
        return v.ok() ? std::string() : WithoutSubject(v.status().message());
      },
      "", "finite number");
}

CLI::Validator FiniteIn(double lo, double hi) {
  return CLI::Validator(
      [lo, hi](std::string& text) {
        auto v = ParseFiniteDouble(text, "");
        if (!v.ok()) return WithoutSubject(v.status().message());
        if (*v < lo || *v > hi) {
          char range[96];
          std::snprintf(range, sizeof(range), " is out of range [%g, %g]", lo, hi);
          return text + range;
        }
        return std::string();
      },
      "", "finite number in range");
}

CLI::Validator ConstructionName() {
  std::vector<std::string> names;
  for (const Construction& c : Constructions()) names.emplace_back(c.name);
  return CLI::IsMember(names);
}

CLI::Validator PointCount() {
  return CLI::Validator(
      [](std::string& text) {
        auto v = ParseInt(text, "", 0, UINT32_MAX);
        if (!v.ok()) return WithoutSubject(v.status().message());
        const Status s = ValidatePointCount(static_cast<uint32_t>(*v));
        return s.ok() ? std::string() : s.message();
      },
      "", "point count");
}

namespace {
bool* parse_only_ran = nullptr;  // ParseOnlyForFuzzing
}  // namespace

void ParseOnlyForFuzzing(bool* ran) { parse_only_ran = ran; }

void OnRun(CLI::App* command, std::function<int()> run) {
  command->callback([run = std::move(run)] {
    if (parse_only_ran != nullptr) {
      *parse_only_ran = true;
      return;
    }
    Finish(run());
  });
}

CLI::App* AddCommand(CLI::App& parent, const std::string& name, const std::string& description) {
  // The footer (exit statuses) is inherited from the parent.
  return parent.add_subcommand(name, description);
}

int RunApp(CLI::App& app, int argc, char** argv) {
  std::vector<std::string> args(argv + 1, argv + argc);
  // Walk the command words first: the word `help` where a command is expected
  // asks for that level's help, and an unknown or missing command gets a
  // message that lists the choices (CLI11 would only say "A subcommand is
  // required").
  const CLI::App* level = &app;
  std::string path;
  for (size_t i = 0;; ++i) {
    if (level->get_subcommands([](const CLI::App*) { return true; }).empty()) break;
    if (i == args.size()) {
      return ReportError(path, Status::InvalidArgument("name a command: " + CommandList(*level) +
                                                       " (alignset" + Prefixed(path) + " --help)"),
                         kExitUsage);
    }
    const std::string& word = args[i];
    if (word == "help") {
      args[i] = "--help";
      break;
    }
    if (!word.empty() && word[0] == '-') break;  // an option: CLI11's to judge
    const CLI::App* next = nullptr;
    try {
      next = level->get_subcommand(word);
    } catch (const CLI::OptionNotFound&) {
      return ReportError(path, Status::InvalidArgument("unknown command '" + word + "'; commands: " +
                                                       CommandList(*level) + " (alignset" +
                                                       Prefixed(path) + " --help)"),
                         kExitUsage);
    }
    level = next;
    path += (path.empty() ? "" : " ") + word;
  }

  const std::vector<std::string> given = args;
  std::reverse(args.begin(), args.end());  // CLI11 takes them last first
  try {
    app.parse(args);
  } catch (const CLI::RuntimeError& e) {  // Finish(): the subcommand already reported
    return e.get_exit_code();
  } catch (const CLI::CallForHelp& e) {
    std::cout << app.help();
    return kExitOk;
  } catch (const CLI::CallForAllHelp& e) {
    std::cout << app.help("", CLI::AppFormatMode::All);
    return kExitOk;
  } catch (const CLI::CallForVersion& e) {
    std::cout << e.what() << std::endl;
    return kExitOk;
  } catch (const CLI::ExtrasError& e) {
    // CLI11 2.1 lists the extras last first; name them as they were typed.
    const std::vector<std::string> extra = app.remaining(true);
    std::string listed;
    for (const std::string& a : given) {
      if (std::find(extra.begin(), extra.end(), a) != extra.end()) listed += " " + a;
    }
    return ReportError(path, Status::InvalidArgument("unexpected argument(s):" + listed), kExitUsage);
  } catch (const CLI::ParseError& e) {
    return ReportError(path, Status::InvalidArgument(e.what()), kExitUsage);
  }
  return kExitOk;
}

}  // namespace alignset::cli

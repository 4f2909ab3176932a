#include <cstdio>

#include "client/commands.h"

namespace alignset::cli {

int ReportError(const std::string& command, const Status& s, int exit_code) {
  std::fprintf(stderr, "alignset %s: %s\n", command.c_str(), s.message().c_str());
  return exit_code;
}

}  // namespace alignset::cli

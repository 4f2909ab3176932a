// The server's flags and environment on any bytes: NUL-separated arguments,
// the environment's ALIGNSET_* variables from the same pool. A status or a
// config; never an exit, an exception or a crash.
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "fuzz/fuzz_args.h"
#include "server/config.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  alignset::fuzz::FuzzArgs line("alignset-server", data, size);
  const std::vector<std::string>& args = line.args;
  // The last argument doubles as every ALIGNSET_* variable's value.
  const std::string env = args.size() > 1 ? args.back() : std::string();
  auto config = alignset::server::ParseServerConfig(
      line.argc(), line.argv.data(),
      [&](const char* name) -> const char* { return std::strncmp(name, "ALIGNSET_", 9) == 0 && !env.empty() ? env.c_str() : nullptr; });
  (void)config;
  return 0;
}

// The server's flags and environment on any bytes: NUL-separated arguments,
// the environment's ALIGNSET_* variables from the same pool. A status or a
// config; never an exit, an exception or a crash.
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "server/config.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  std::vector<std::string> args = {"alignset-server"};
  std::string current;
  for (size_t i = 0; i < size && args.size() < 64; ++i) {
    if (data[i] == 0) {
      args.push_back(current);
      current.clear();
    } else {
      current.push_back(static_cast<char>(data[i]));
    }
  }
  if (!current.empty()) args.push_back(current);
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  // The last argument doubles as every ALIGNSET_* variable's value.
  const std::string env = args.size() > 1 ? args.back() : std::string();
  auto config = alignset::server::ParseServerConfig(
      static_cast<int>(args.size()), argv.data(),
      [&](const char* name) -> const char* { return std::strncmp(name, "ALIGNSET_", 9) == 0 && !env.empty() ? env.c_str() : nullptr; });
  (void)config;
  return 0;
}

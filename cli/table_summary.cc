#include "cli/table_summary.h"

#include <cstdio>
#include <filesystem>
#include <string>

namespace alignset::cli {

void PrintTableSummary(const SetTable& table, const std::string& path) {
  std::printf("sections       %zu\n", table.sections().size());
  for (const TableSection& s : table.sections()) {
    const size_t held = s.keys.empty() ? TableSpaceKeys(s.space) : s.keys.size();
    std::printf("  N=%-6u %-13s %-13s %zu keys%s\n", s.n, s.construction.c_str(), TableSpaceName(s.space), held,
                s.keys.empty() ? "" : (" of " + std::to_string(TableSpaceKeys(s.space))).c_str());
  }
  std::printf("bytes          %llu\n", static_cast<unsigned long long>(std::filesystem::file_size(path)));
  std::printf("format         version %u, crc32c\n", table.format_version());
  std::printf("wrote          %s\n", path.c_str());
}

}  // namespace alignset::cli

#include "cli/table_summary.h"

#include <cstdio>
#include <filesystem>

namespace alignset::cli {

void PrintTableSummary(const SetTable& table, const std::string& path) {
  std::printf("sections       %zu\n", table.sections().size());
  for (const TableSection& s : table.sections()) {
    std::printf("  N=%-6u %-13s %-13s %u keys\n", s.n, s.construction.c_str(), TableSpaceName(s.space),
                TableSpaceKeys(s.space));
  }
  std::printf("bytes          %llu\n", static_cast<unsigned long long>(std::filesystem::file_size(path)));
  std::printf("format         version %u, crc32c\n", SetTable::kFormatVersion);
  std::printf("wrote          %s\n", path.c_str());
}

}  // namespace alignset::cli

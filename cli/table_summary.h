#pragma once

#include <alignset/set_table.h>

#include <string>

namespace alignset::cli {

// What `export` and `table` print after writing a table file: its sections,
// size, format and path.
void PrintTableSummary(const SetTable& table, const std::string& path);

}  // namespace alignset::cli

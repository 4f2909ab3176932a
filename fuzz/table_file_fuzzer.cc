// SetTable::Parse on any bytes: a status or a table, and an accepted table
// serializes back to the same bytes (the format has one encoding).
#include <alignset/set_table.h>

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <span>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  auto table = alignset::SetTable::Parse(std::span<const uint8_t>(data, size));
  if (!table.ok()) return 0;
  const std::vector<uint8_t> again = (*table)->Serialize();
  if (again.size() != size || !std::equal(again.begin(), again.end(), data)) std::abort();
  return 0;
}

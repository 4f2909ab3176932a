#include "cli/table_space.h"

namespace alignset::cli {

SpaceShape ShapeOf(TableSpace space) {
  switch (space) {
    case TableSpace::kOneDirection: return {1, AngleGrid::kWholeDegree};
    case TableSpace::kOneQuarter: return {1, AngleGrid::kQuarterDegree};
    case TableSpace::kTwoDirections: return {2, AngleGrid::kWholeDegree};
  }
  return {1, AngleGrid::kWholeDegree};
}

StatusOr<std::vector<TableSpace>> ParseTableSpaces(const std::vector<std::string>& names) {
  std::vector<TableSpace> spaces;
  for (const std::string& name : names) {
    auto space = ParseTableSpace(name);
    if (!space.ok()) return space.status();
    spaces.push_back(*space);
  }
  return spaces;
}

}  // namespace alignset::cli

#pragma once

#include <alignset/set_table.h>
#include <alignset/status.h>

#include <string>
#include <vector>

#include "core/align/canonical.h"

namespace alignset::cli {

// A table space's keys as core enumerates them: one or two directions, on
// the whole- or quarter-degree grid. `table` builds them, `export` reads them.
struct SpaceShape {
  int directions;
  AngleGrid grid;
};
SpaceShape ShapeOf(TableSpace space);

// The spaces of --space, in order; the first name that is none, refused as
// ParseTableSpace refuses it.
StatusOr<std::vector<TableSpace>> ParseTableSpaces(const std::vector<std::string>& names);

}  // namespace alignset::cli

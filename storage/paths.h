#pragma once

#include <string>

#include "core/util/status.h"

namespace alignset::storage {

// Where the server keeps its cache when no path is configured:
// $ALIGNSET_DATA_DIR/alignset.sqlite, else $XDG_DATA_HOME/alignset/alignset.sqlite
// (XDG_DATA_HOME only when absolute, as the XDG spec asks), else
// ~/.local/share/alignset/alignset.sqlite. Creates the directory.
StatusOr<std::string> DefaultDatabasePath();

}  // namespace alignset::storage

#pragma once

// A cache file that `cache merge` and `cache recover` build under
// OUT.partial (with SQLite's -wal and -shm beside it) and rename when
// complete, so an interrupted run never leaves a half-written OUT.
#include <string>

#include "core/util/status.h"

namespace alignset::storage {

// Makes room for `partial`: an existing file (or its -wal/-shm) may be another
// run's work in progress, so it is refused unless `overwrite`, and removed then.
Status ClearPartialFile(const std::string& partial, bool overwrite);

// Removes `partial` and its -wal/-shm, after a run that failed.
void RemovePartialFile(const std::string& partial);

}  // namespace alignset::storage

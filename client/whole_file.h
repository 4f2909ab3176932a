#pragma once

#include <string>
#include <string_view>

#include <alignset/status.h>

namespace alignset {

// Writes `data` as the whole content of `path`, so that a reader never sees
// a half-written file: into a temporary file beside it (named by the
// process, so two writers of one path do not share it), synced, then
// renamed over the path. A crash or a kill mid-write leaves the old file or
// none, plus at most a stray temporary.
//
// A path that exists and is not a regular file (a device, a pipe: -o
// /dev/null) is written into as it is: the rename would replace it with a
// regular file (as root, /dev/null itself).
//
// INVALID_ARGUMENT naming the path and the system's reason when it cannot be
// written; the temporary is removed then.
Status WriteWholeFile(const std::string& path, std::string_view data);

}  // namespace alignset

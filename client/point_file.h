#pragma once

#include <string>

#include "core/util/point_set.h"
#include "core/util/status.h"

namespace alignset::cli {

// Point-set files. By extension: ".npy" is a NumPy array of shape (N, 2),
// little-endian float64; anything else is UTK's text format, one "x y" line
// per point with '#' comment lines.
//
// Writes go to a temporary file beside the target, then rename(2): a reader
// (or a crash) never sees half a file.
Status WritePointFile(const std::string& path, const PointSet& points,
                      const std::string& comment = "");
StatusOr<PointSet> ReadPointFile(const std::string& path);

}  // namespace alignset::cli

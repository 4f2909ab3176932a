#pragma once

#include <string>
#include <vector>

#include "core/util/status.h"

namespace alignset::render {

// Writes a C-order little-endian float64 NumPy array of the given shape
// (images: {H, W}), through a temporary file and rename(2) so that a reader
// never sees half a file.
Status WriteNpy(const std::string& path, const std::vector<size_t>& shape,
                const std::vector<double>& data);

// Reads what WriteNpy writes (float64, C order, any rank); the shape comes
// back in `shape`.
StatusOr<std::vector<double>> ReadNpy(const std::string& path, std::vector<size_t>* shape);

}  // namespace alignset::render

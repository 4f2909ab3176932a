#pragma once

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "core/util/status.h"

namespace alignset::cli {

// A NumPy .npy array as the CLI reads it: little-endian float64 or float32,
// C or Fortran order, any rank. `values` is always in C order (the last index
// fastest), converted to double. Shared by point-set files ((N, 2) arrays)
// and integrand patches ((H, W) grids).
struct NpyArray {
  std::vector<size_t> shape;
  std::vector<double> values;
};

// "(64, 48)", "(5,)": a shape as NumPy prints it.
std::string NpyShapeText(const std::vector<size_t>& shape);

// Checks an array's shape before its values are copied (so an oversized
// array is refused without allocating it); its error is returned as is.
using NpyShapeCheck = std::function<Status(const std::vector<size_t>& shape)>;

// Parses the bytes of a .npy file; `path` names it in errors.
StatusOr<NpyArray> ParseNpyArray(const std::string& data, const std::string& path,
                                 const NpyShapeCheck& check_shape = nullptr);

}  // namespace alignset::cli

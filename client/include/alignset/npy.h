#pragma once

// NumPy .npy files, the one reader and writer of the whole project: point
// sets ((N, 2) and (m, N, 2) arrays), integrand patches and rendered images
// ((H, W) grids). Reads little-endian float64 or float32, C or Fortran order,
// any rank, format versions 1 to 3; writes version 1.0 float64 in C order,
// byte for byte as numpy.save does. Part of the client library (also linked
// by the command line without the service); needs nothing but <alignset/status.h>.

#include <alignset/status.h>

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

namespace alignset {

// A .npy array as read: `values` is always in C order (the last index
// fastest), converted to double.
struct NpyArray {
  std::vector<size_t> shape;
  std::vector<double> values;
};

// "(64, 48)", "(5,)": a shape as NumPy prints it.
std::string NpyShapeText(const std::vector<size_t>& shape);

// The header (magic, version 1.0, length, dictionary padded with spaces and
// a newline to a multiple of 64 bytes) of an array of `shape` whose items
// are `descr` ('<f8' unless told), in C order unless `fortran_order`; the
// body follows it directly.
std::string NpyHeader(const std::vector<size_t>& shape, bool fortran_order = false,
                      const std::string& descr = "<f8");

// Checks an array's shape before its values are copied (so an oversized
// array is refused without allocating it); its error is returned as is.
using NpyShapeCheck = std::function<Status(const std::vector<size_t>& shape)>;

// Parses the bytes of a .npy file; `path` names it in errors.
StatusOr<NpyArray> ParseNpyArray(const std::string& data, const std::string& path,
                                 const NpyShapeCheck& check_shape = nullptr);

// Reads and parses a .npy file.
StatusOr<NpyArray> ReadNpy(const std::string& path, const NpyShapeCheck& check_shape = nullptr);

// Writes a C-order float64 array of `shape` (images: {H, W}) through a
// temporary file and rename(2), so that a reader never sees half a file.
// INVALID_ARGUMENT when the shape does not hold data.size() values or the
// file cannot be written.
Status WriteNpy(const std::string& path, const std::vector<size_t>& shape,
                const std::vector<double>& data);

}  // namespace alignset

#pragma once

// Writes small NumPy .npy files for the CLI tests: the project's one .npy
// header (<alignset/npy.h>), then the values as given, so a test can write
// the Fortran order the writer itself never produces.

#include <alignset/npy.h>

#include <fstream>
#include <string>
#include <vector>

namespace alignset::test_support {

// A float64 .npy file of `shape`; `values` in the file's own memory order
// (C order unless `fortran`).
inline void WriteNpy(const std::string& path, const std::vector<size_t>& shape,
                     const std::vector<double>& values, bool fortran = false) {
  std::ofstream out(path, std::ios::binary);
  out << NpyHeader(shape, fortran);
  out.write(reinterpret_cast<const char*>(values.data()),
            static_cast<std::streamsize>(values.size() * sizeof(double)));
}

}  // namespace alignset::test_support

#pragma once

// Writes small NumPy .npy files for the CLI tests, independently of the
// reader under test (client/npy_array.cc).

#include <cstdint>
#include <fstream>
#include <string>
#include <vector>

namespace alignset::test_support {

// A float64 .npy file of `shape`; `values` in the file's own memory order
// (C order unless `fortran`).
inline void WriteNpy(const std::string& path, const std::vector<size_t>& shape,
                     const std::vector<double>& values, bool fortran = false) {
  std::string s = "(";
  for (size_t i = 0; i < shape.size(); ++i) s += (i ? ", " : "") + std::to_string(shape[i]);
  s += shape.size() == 1 ? ",)" : ")";
  std::string dict = "{'descr': '<f8', 'fortran_order': " + std::string(fortran ? "True" : "False") +
                     ", 'shape': " + s + ", }";
  const size_t total = 10 + dict.size() + 1;
  dict.append((64 - total % 64) % 64, ' ');
  dict.push_back('\n');
  std::ofstream out(path, std::ios::binary);
  out.write("\x93NUMPY\x01\x00", 8);
  const uint16_t len = static_cast<uint16_t>(dict.size());
  out.put(static_cast<char>(len & 0xff));
  out.put(static_cast<char>(len >> 8));
  out << dict;
  out.write(reinterpret_cast<const char*>(values.data()),
            static_cast<std::streamsize>(values.size() * sizeof(double)));
}

}  // namespace alignset::test_support

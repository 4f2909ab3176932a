// ParseNpyArray on any bytes, with the shape check the CLI uses (at most
// 2^20 values): a status or an array holding as many values as its shape.
#include <alignset/npy.h>

#include <cstdint>
#include <cstdlib>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string bytes(reinterpret_cast<const char*>(data), size);
  auto array = alignset::ParseNpyArray(bytes, "fuzz.npy", [](const std::vector<size_t>& shape) {
    size_t count = 1;
    for (size_t d : shape) {
      if (d != 0 && count > (size_t{1} << 20) / d) return alignset::Status::InvalidArgument("too large");
      count *= d;
    }
    return count <= (size_t{1} << 20) ? alignset::Status::Ok() : alignset::Status::InvalidArgument("too large");
  });
  if (!array.ok()) return 0;
  size_t count = 1;
  for (size_t d : array->shape) count *= d;
  if (count != array->values.size()) std::abort();
  return 0;
}

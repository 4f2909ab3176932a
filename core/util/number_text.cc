#include "core/util/number_text.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>

namespace alignset {

StatusOr<double> ParseFiniteDouble(const std::string& text, const std::string& what) {
  if (text.empty()) return Status::InvalidArgument(what + ": empty value");
  char* end = nullptr;
  errno = 0;
  const double v = std::strtod(text.c_str(), &end);
  if (end == text.c_str() || *end != '\0') {
    return Status::InvalidArgument(what + ": '" + text + "' is not a number");
  }
  if (!std::isfinite(v) || errno == ERANGE) {
    return Status::InvalidArgument(what + ": '" + text + "' is not a finite number");
  }
  return v;
}

StatusOr<int64_t> ParseInt(const std::string& text, const std::string& what, int64_t lo, int64_t hi) {
  if (text.empty()) return Status::InvalidArgument(what + ": empty value");
  char* end = nullptr;
  errno = 0;
  const long long v = std::strtoll(text.c_str(), &end, 10);
  if (end == text.c_str() || *end != '\0' || errno == ERANGE) {
    return Status::InvalidArgument(what + ": '" + text + "' is not an integer");
  }
  if (v < lo || v > hi) {
    return Status::InvalidArgument(what + ": " + text + " is out of range [" + std::to_string(lo) +
                                   ", " + std::to_string(hi) + "]");
  }
  return static_cast<int64_t>(v);
}

}  // namespace alignset

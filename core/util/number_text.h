#pragma once

#include <cstdint>
#include <string>

#include "core/util/status.h"

namespace alignset {

// Checked conversions of flag and environment values, shared by the command
// line and the server's configuration. `what` names the value in the error
// (e.g. "--workers").

// A finite real number; rejects empty text, "nan", "inf", overflow and
// trailing garbage.
StatusOr<double> ParseFiniteDouble(const std::string& text, const std::string& what);

// A base-10 integer in [lo, hi]; rejects empty text, overflow and trailing
// garbage.
StatusOr<int64_t> ParseInt(const std::string& text, const std::string& what, int64_t lo, int64_t hi);

}  // namespace alignset

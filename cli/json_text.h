#pragma once

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

namespace alignset::cli {

// The few JSON pieces the analysis commands print (numbers, strings and
// arrays of numbers); NaN and infinities become null, as JSON has neither.
inline std::string JsonNumber(double v) {
  if (!std::isfinite(v)) return "null";
  char text[32];
  std::snprintf(text, sizeof(text), "%.6g", v);
  return text;
}

inline std::string JsonString(const std::string& s) {
  std::string out = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if (static_cast<unsigned char>(c) < 0x20) {
      char esc[8];
      std::snprintf(esc, sizeof(esc), "\\u%04x", c);
      out += esc;
    } else {
      out += c;
    }
  }
  return out + "\"";
}

inline std::string JsonArray(const std::vector<double>& values) {
  std::string out = "[";
  for (size_t i = 0; i < values.size(); ++i) out += (i ? "," : "") + JsonNumber(values[i]);
  return out + "]";
}

}  // namespace alignset::cli

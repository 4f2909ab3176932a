#pragma once

// A command line from fuzz bytes, shared by the flag fuzzers: NUL-separated
// arguments after a program name, at most 64, with an argv that points into
// them (null-terminated, as main's).
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace alignset::fuzz {

struct FuzzArgs {
  FuzzArgs(const char* program, const uint8_t* data, size_t size) : args{program} {
    std::string current;
    for (size_t i = 0; i < size && args.size() < 64; ++i) {
      if (data[i] == 0) {
        args.push_back(current);
        current.clear();
      } else {
        current.push_back(static_cast<char>(data[i]));
      }
    }
    if (!current.empty()) args.push_back(current);
    for (std::string& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
  }
  FuzzArgs(const FuzzArgs&) = delete;
  FuzzArgs& operator=(const FuzzArgs&) = delete;

  int argc() const { return static_cast<int>(args.size()); }

  std::vector<std::string> args;
  std::vector<char*> argv;
};

}  // namespace alignset::fuzz

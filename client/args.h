#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "core/util/number_text.h"
#include "core/util/status.h"

namespace alignset::cli {

// Command-line flags of one subcommand: "--name value", "--name=value",
// repeated flags, bare "--switch" for declared switches, and positionals.
// Every conversion is checked and reports the flag it came from.
class Args {
 public:
  // `switches` are flags that take no value.
  static StatusOr<Args> Parse(int argc, char** argv, const std::vector<std::string>& known_flags,
                              const std::vector<std::string>& switches = {});

  bool Has(const std::string& flag) const { return values_.count(flag) > 0; }
  const std::vector<std::string>& All(const std::string& flag) const;
  const std::vector<std::string>& positionals() const { return positionals_; }

  StatusOr<std::string> String(const std::string& flag, const std::string& fallback) const;
  StatusOr<int64_t> Int(const std::string& flag, int64_t fallback, int64_t lo, int64_t hi) const;
  StatusOr<double> Double(const std::string& flag, double fallback) const;
  // Every value of a repeated flag, each a finite real number.
  StatusOr<std::vector<double>> Doubles(const std::string& flag) const;

 private:
  std::map<std::string, std::vector<std::string>> values_;
  std::vector<std::string> positionals_;
};

}  // namespace alignset::cli

#include "client/args.h"

#include <algorithm>

namespace alignset::cli {

StatusOr<Args> Args::Parse(int argc, char** argv, const std::vector<std::string>& known_flags,
                           const std::vector<std::string>& switches) {
  Args args;
  auto known = [&](const std::string& f) {
    return std::find(known_flags.begin(), known_flags.end(), f) != known_flags.end();
  };
  auto is_switch = [&](const std::string& f) {
    return std::find(switches.begin(), switches.end(), f) != switches.end();
  };
  for (int i = 0; i < argc; ++i) {
    std::string a = argv[i];
    if (a.rfind("--", 0) != 0 || a == "--") {
      args.positionals_.push_back(a);
      continue;
    }
    std::string name = a.substr(2), value;
    bool has_value = false;
    if (auto eq = name.find('='); eq != std::string::npos) {
      value = name.substr(eq + 1);
      name = name.substr(0, eq);
      has_value = true;
    }
    if (is_switch(name)) {
      if (has_value) return Status::InvalidArgument("--" + name + " takes no value");
      args.values_[name].push_back("1");
      continue;
    }
    if (!known(name)) return Status::InvalidArgument("unknown option --" + name);
    if (!has_value) {
      if (i + 1 >= argc) return Status::InvalidArgument("--" + name + " needs a value");
      value = argv[++i];
    }
    args.values_[name].push_back(value);
  }
  return args;
}

const std::vector<std::string>& Args::All(const std::string& flag) const {
  static const std::vector<std::string> kEmpty;
  auto it = values_.find(flag);
  return it == values_.end() ? kEmpty : it->second;
}

StatusOr<std::string> Args::String(const std::string& flag, const std::string& fallback) const {
  const auto& v = All(flag);
  if (v.empty()) return fallback;
  if (v.size() > 1) return Status::InvalidArgument("--" + flag + " given more than once");
  return v.front();
}

StatusOr<int64_t> Args::Int(const std::string& flag, int64_t fallback, int64_t lo, int64_t hi) const {
  const auto& v = All(flag);
  if (v.empty()) return fallback;
  if (v.size() > 1) return Status::InvalidArgument("--" + flag + " given more than once");
  return ParseInt(v.front(), "--" + flag, lo, hi);
}

StatusOr<double> Args::Double(const std::string& flag, double fallback) const {
  const auto& v = All(flag);
  if (v.empty()) return fallback;
  if (v.size() > 1) return Status::InvalidArgument("--" + flag + " given more than once");
  return ParseFiniteDouble(v.front(), "--" + flag);
}

StatusOr<std::vector<double>> Args::Doubles(const std::string& flag) const {
  std::vector<double> out;
  for (const std::string& s : All(flag)) {
    auto d = ParseFiniteDouble(s, "--" + flag);
    if (!d.ok()) return d.status();
    out.push_back(*d);
  }
  return out;
}

}  // namespace alignset::cli

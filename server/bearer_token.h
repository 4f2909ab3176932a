#pragma once

#include <string>
#include <string_view>

namespace alignset::server {

// Whether an authorization value (gRPC metadata or an HTTP header) is
// "Bearer <token>", compared in time independent of where they differ.
inline bool BearerTokenMatches(std::string_view value, const std::string& token) {
  constexpr std::string_view kPrefix = "Bearer ";
  if (value.substr(0, kPrefix.size()) != kPrefix) return false;
  const std::string_view given = value.substr(kPrefix.size());
  if (given.size() != token.size()) return false;
  unsigned char diff = 0;
  for (size_t i = 0; i < given.size(); ++i) diff |= static_cast<unsigned char>(given[i] ^ token[i]);
  return diff == 0;
}

}  // namespace alignset::server

#include "server/construction.h"

#include "server/log_text.h"

namespace alignset::server {

StatusOr<Construction> ParseConstruction(const std::string& name) {
  if (name.empty() || name == "optimized") return Construction::kOptimized;
  if (name == "lattice") return Construction::kLattice;
  // Quoted: the name comes from the client (escaped, cut after 64 bytes).
  return Status::InvalidArgument("unknown construction " + Quoted(name) +
                                 ": the known ones are 'optimized' (the default, also '') and "
                                 "'lattice'");
}

const char* ConstructionName(Construction c) {
  return c == Construction::kLattice ? "lattice" : "optimized";
}

Construction ConstructionOfProfile(const std::string& profile) {
  return profile == kLatticeProfile ? Construction::kLattice : Construction::kOptimized;
}

}  // namespace alignset::server

#include "server/construction.h"

#include "server/log_text.h"

namespace alignset::server {

StatusOr<Construction> ParseConstruction(const std::string& name) {
  if (name.empty() || name == "optimized") return Construction::kOptimized;
  if (name == "lattice") return Construction::kLattice;
  if (name == "net") return Construction::kNet;
  if (name == "tent-lattice") return Construction::kTentLattice;
  // Quoted: the name comes from the client (escaped, cut after 64 bytes).
  return Status::InvalidArgument("unknown construction " + Quoted(name) +
                                 ": the known ones are 'optimized' (the default, also ''), "
                                 "'lattice', 'tent-lattice' and 'net'");
}

const char* ConstructionName(Construction c) {
  switch (c) {
    case Construction::kLattice: return "lattice";
    case Construction::kNet: return "net";
    case Construction::kTentLattice: return "tent-lattice";
    case Construction::kOptimized: break;
  }
  return "optimized";
}

Status ValidateConstructionSize(Construction c, uint32_t n) {
  if (c == Construction::kNet && (n < 16 || n > 65536 || (n & (n - 1)) != 0)) {
    return Status::InvalidArgument("construction 'net' needs N a power of two from 16 to 65536, got " +
                                   std::to_string(n));
  }
  return Status::Ok();
}

Construction ConstructionOfProfile(const std::string& profile) {
  if (profile == kLatticeProfile) return Construction::kLattice;
  if (profile == kNetProfile) return Construction::kNet;
  if (profile == kTentLatticeProfile) return Construction::kTentLattice;
  return Construction::kOptimized;
}

}  // namespace alignset::server

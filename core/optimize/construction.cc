#include "core/optimize/construction.h"

#include <iterator>
#include <string>

#include "core/optimize/aligned_lattice.h"
#include "core/optimize/lattice_sequence.h"

namespace alignset {
namespace {

// The profiles are literals, not formatted from name, version and window, so
// that a glance at this table shows the cache keys every stored set has.
constexpr Construction kConstructions[] = {
    {ConstructionKind::kOptimized, "optimized", "optimized set", 0, 0.0, ""},
    {ConstructionKind::kLattice, "lattice", "rank-1 lattice", 2, 1.0, "lattice-v2-w1"},
    {ConstructionKind::kTentLattice, "tent-lattice", "tent-folded rank-1 lattice", 1, kTentLatticeWindowDeg,
     "tent-lattice-v1-w2"},
    {ConstructionKind::kNet, "net", "(0,m,2)-net", 1, 1.0, "net-v1-w1"},
    {ConstructionKind::kLatticeSequence, "lattice-sequence", "rank-1 lattice sequence", 1, 1.0,
     "lattice-sequence-v1-w1"},
};

}  // namespace

std::span<const Construction> Constructions() { return kConstructions; }

const Construction& ConstructionOf(ConstructionKind kind) {
  for (const Construction& c : kConstructions) {
    if (c.kind == kind) return c;
  }
  return kConstructions[0];
}

const Construction* FindConstruction(std::string_view name) {
  if (name.empty()) return &kConstructions[0];
  for (const Construction& c : kConstructions) {
    if (c.name == name) return &c;
  }
  return nullptr;
}

const Construction& ConstructionOfProfile(std::string_view profile) {
  for (const Construction& c : kConstructions) {
    if (!c.optimized() && c.profile == profile) return c;
  }
  return kConstructions[0];
}

std::string KnownConstructionNames() {
  std::string out;
  const size_t count = std::size(kConstructions);
  for (size_t i = 0; i < count; ++i) {
    if (i > 0) out += i + 1 == count ? " and " : ", ";
    out += "'" + std::string(kConstructions[i].name) + "'";
    if (i == 0) out += " (the default, also '')";
  }
  return out;
}

Status Construction::ValidateSize(uint32_t n) const {
  if (kind == ConstructionKind::kNet && (n < 16 || n > 65536 || (n & (n - 1)) != 0)) {
    return Status::InvalidArgument("construction 'net' needs N a power of two from 16 to 65536, got " +
                                   std::to_string(n));
  }
  if (kind == ConstructionKind::kLatticeSequence && (n < 16 || n > kLatticeSequenceMaxPoints)) {
    return Status::InvalidArgument("construction 'lattice-sequence' needs N from 16 to " +
                                   std::to_string(kLatticeSequenceMaxPoints) + ", got " + std::to_string(n));
  }
  return Status::Ok();
}

}  // namespace alignset

#pragma once

// Small tables made the way `alignset export` makes them: the canonical
// keys' lattices chosen by the core, or sets of points.
#include <alignset/set_table.h>

#include <memory>
#include <vector>

#include "core/align/canonical.h"
#include "core/optimize/aligned_lattice.h"
#include "core/sampling/owen_sobol.h"

namespace alignset::testing {

inline std::vector<std::vector<double>> KeyDirections(TableSpace space) {
  std::vector<std::vector<double>> out;
  const int count = space == TableSpace::kTwoDirections ? 2 : 1;
  const AngleGrid grid = space == TableSpace::kOneQuarter ? AngleGrid::kQuarterDegree : AngleGrid::kWholeDegree;
  for (size_t i = 0; i < CanonicalKeyCount(count, grid); ++i) {
    const CanonicalDirections k = CanonicalKeyAt(count, i, grid);
    out.push_back(count == 1 ? std::vector<double>{Phi1Degrees(k)} : std::vector<double>{Phi1Degrees(k), Phi2Degrees(k)});
  }
  return out;
}

inline TableSection LatticeSection(uint32_t n, TableSpace space, bool folded = false) {
  TableSection s;
  s.n = n;
  s.construction = folded ? "tent-lattice" : "lattice";
  s.space = space;
  AlignedLatticeOptions o;
  o.folded = folded;
  o.window_deg = DefaultLatticeWindowDeg(folded);
  o.threads = 2;
  auto choices = ChooseAlignedLatticeGenerators(n, KeyDirections(space), o);
  for (const AlignedLatticeChoice& c : *choices) s.generators.push_back(c.generator);
  return s;
}

// Owen-Sobol sets standing in for optimized ones (the table does not care
// how the points were made).
inline TableSection PointsSection(uint32_t n, TableSpace space) {
  TableSection s;
  s.n = n;
  s.construction = "optimized";
  s.space = space;
  for (uint32_t k = 0; k < TableSpaceKeys(space); ++k) s.sets.push_back(OwenScrambledSobol(n, 1000 + k));
  return s;
}

}  // namespace alignset::testing

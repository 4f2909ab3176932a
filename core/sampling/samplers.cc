#include "core/sampling/samplers.h"

#include <functional>

#include "core/sampling/owen_sobol.h"
#include "core/sampling/pmj02.h"
#include "core/sampling/poisson_disk.h"
#include "core/sampling/rank1_lattice.h"
#include "core/sampling/sampler_radical_inverse.h"
#include "core/sampling/sampler_stratified.h"
#include "core/sampling/sampler_util.h"

namespace alignset {
namespace {

using Maker = std::function<StatusOr<PointSet>(uint32_t n, uint64_t seed)>;

struct Entry {
  SamplerInfo info;
  Maker make;
};

const std::vector<Entry>& Entries() {
  static const std::vector<Entry> entries = {
      {{"random", "white noise (any N)"}, RandomPoints},
      {{"grid", "centres of m x m strata, no randomness (square N)"},
       [](uint32_t n, uint64_t) { return RegularGrid(n); }},
      {{"uniform-jitter", "m x m grid shifted by one shared random offset (square N)"},
       UniformJitter},
      {{"jittered", "random jitter: one uniform point per m x m stratum (square N)"}, Jittered},
      {{"n-rooks", "one point per row and column, Latin hypercube (any N)"}, NRooks},
      {{"multi-jittered", "Chiu-Shirley-Wang multi-jittered on m x k cells, m k = N (any N)"},
       MultiJittered},
      {{"cmj", "Kensler's correlated multi-jittered on m x k cells, m k = N (any N)"},
       CorrelatedMultiJittered},
      {{"halton", "Halton, bases 2 and 3, unscrambled; seed ignored (any N)"},
       [](uint32_t n, uint64_t s) { return Halton(n, s, false); }},
      {{"halton-scrambled", "Halton with random digit permutations (any N)"},
       [](uint32_t n, uint64_t s) { return Halton(n, s, true); }},
      {{"hammersley", "Hammersley (i/N, base 2), unscrambled; seed ignored (any N)"},
       [](uint32_t n, uint64_t s) { return Hammersley(n, s, false); }},
      {{"hammersley-scrambled", "Hammersley with random digit permutations (any N)"},
       [](uint32_t n, uint64_t s) { return Hammersley(n, s, true); }},
      {{"sobol", "Sobol (0,2)-sequence, unscrambled; seed ignored (any N)"},
       [](uint32_t n, uint64_t) { return Sobol(n); }},
      {{"owen-sobol", "Sobol with hash-based Owen scrambling, Burley 2020 (any N)"},
       [](uint32_t n, uint64_t s) -> StatusOr<PointSet> {
         if (Status st = CheckSampleCount("owen-sobol", n); !st.ok()) return st;
         return OwenScrambledSobol(n, s);
       }},
      {{"pmj02", "progressive multi-jittered (0,2) sequence (any N)"},
       [](uint32_t n, uint64_t s) { return Pmj02(n, s, 1); }},
      {{"pmj02bn", "pmj02 with blue-noise best-candidate selection (any N)"},
       [](uint32_t n, uint64_t s) { return Pmj02(n, s, kPmj02bnCandidates); }},
      {{"rank1-lattice", "rank-1 lattice, Fibonacci or best Korobov, CP-shifted (any N)"},
       Rank1Lattice},
      {{"poisson-dart", "Poisson disk by dart throwing on the torus (any N)"},
       [](uint32_t n, uint64_t s) { return PoissonDiskDartThrowing(n, s); }},
      {{"poisson-bridson", "Poisson disk by Bridson's algorithm on the torus (any N)"},
       [](uint32_t n, uint64_t s) { return PoissonDiskBridson(n, s); }},
  };
  return entries;
}

}  // namespace

const std::vector<SamplerInfo>& Samplers() {
  static const std::vector<SamplerInfo> infos = [] {
    std::vector<SamplerInfo> v;
    for (const Entry& e : Entries()) v.push_back(e.info);
    return v;
  }();
  return infos;
}

std::vector<std::string> SamplerNames() {
  std::vector<std::string> names;
  for (const Entry& e : Entries()) names.push_back(e.info.name);
  return names;
}

StatusOr<PointSet> Sample(const std::string& name, uint32_t n, uint64_t seed) {
  for (const Entry& e : Entries()) {
    if (e.info.name == name) return e.make(n, seed);
  }
  std::string known;
  for (const Entry& e : Entries()) known += (known.empty() ? "" : ", ") + e.info.name;
  return Status::InvalidArgument("unknown sampler '" + name + "' (known: " + known + ")");
}

}  // namespace alignset

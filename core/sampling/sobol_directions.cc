#include "core/sampling/sobol_directions.h"

#include <boost/random/sobol.hpp>

namespace alignset {

static_assert(kSobolMaxDimensions == boost::random::detail::qrng_tables::sobol::max_dimension);

std::vector<uint32_t> SobolDirectionNumbers(uint32_t dimensions) {
  // Boost builds the direction numbers from the table (Bratley and Fox's
  // recurrence) digit-major: digit j of dimension d at j * dimensions + d.
  using Table = boost::random::qrng_detail::sobol_lattice<uint32_t, kSobolDigits,
                                                     boost::random::detail::qrng_tables::sobol>;
  std::vector<uint32_t> v(static_cast<size_t>(dimensions) * kSobolDigits);
  if (dimensions == 0) return v;
  const Table table(dimensions);
  for (uint32_t d = 0; d < dimensions; ++d) {
    for (uint32_t j = 0; j < kSobolDigits; ++j) {
      v[static_cast<size_t>(d) * kSobolDigits + j] = *table.iter_at(static_cast<size_t>(j) * dimensions + d);
    }
  }
  return v;
}

}  // namespace alignset

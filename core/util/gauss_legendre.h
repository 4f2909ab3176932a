#pragma once

#include <vector>

namespace alignset {

// Gauss-Legendre nodes (ascending) and weights on [-1, 1]: Newton on the
// three-term recurrence, started from the Chebyshev-like asymptotic guess.
// Exact for polynomials of degree < 2 count.
void GaussLegendre(int count, std::vector<double>* nodes, std::vector<double>* weights);

}  // namespace alignset

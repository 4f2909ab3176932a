#include "core/util/gauss_legendre.h"

#include <cmath>

#include "core/util/angles.h"

namespace alignset {
namespace {

// P_count(x) and its derivative, by the three-term recurrence.
void LegendreAt(int count, double x, double* p, double* dp) {
  double p0 = 1.0, p1 = x;
  for (int k = 2; k <= count; ++k) {
    const double p2 = ((2.0 * k - 1.0) * x * p1 - (k - 1.0) * p0) / k;
    p0 = p1;
    p1 = p2;
  }
  *p = p1;
  *dp = count * (x * p1 - p0) / (x * x - 1.0);
}

}  // namespace

void GaussLegendre(int count, std::vector<double>* nodes, std::vector<double>* weights) {
  nodes->assign(count, 0.0);
  weights->assign(count, 0.0);
  for (int i = 0; i < (count + 1) / 2; ++i) {
    double x = std::cos(kPi * (i + 0.75) / (count + 0.5));
    double p = 0.0, dp = 1.0;
    for (int iter = 0; iter < 100; ++iter) {
      LegendreAt(count, x, &p, &dp);
      const double dx = p / dp;
      x -= dx;
      if (std::abs(dx) < 1e-16) break;
    }
    // The derivative at the converged node, for the weight.
    LegendreAt(count, x, &p, &dp);
    const double w = 2.0 / ((1.0 - x * x) * dp * dp);
    (*nodes)[i] = -x;
    (*nodes)[count - 1 - i] = x;
    (*weights)[i] = (*weights)[count - 1 - i] = w;
  }
}

}  // namespace alignset

#pragma once

#include <vector>

namespace alignset {

// The modified Bessel functions the von Mises density needs, finite for every
// kappa >= 0 (std::cyl_bessel_i overflows past kappa ~ 700, and its ratio
// loses all digits long before). Below kBesselSwitch they are
// std::cyl_bessel_i; above, the Hankel asymptotic series of e^-k I_nu(k), whose
// smallest term there is ~e^-2k, below double precision.
inline constexpr double kBesselSwitch = 30.0;
// log I0(kappa).
double LogBesselI0(double kappa);
// A(kappa) = I1(kappa) / I0(kappa), in [0, 1): the mean resultant length of
// the von Mises distribution.
double BesselRatio(double kappa);

// q(x | mu, kappa) = exp(kappa cos(x - mu)) / (2 pi I0(kappa)) on [0, 2pi),
// fitted to a target density p by minimising the reverse KL divergence plus
// a penalty on kappa (supplement Eqs. 1-4):
//   D(mu, kappa) = KL(q || p) + lambda kappa^2
//                = E_q[log q] - E_q[log p] + lambda kappa^2.
// p is given as log p at the centres x_i = (i + 1/2) 2pi / n of n equal bins;
// E_q[g] is the midpoint sum  sum_i q(x_i) g(x_i) 2pi / n  (spectrally
// accurate for periodic g while q is wider than a few bins: see
// MaxResolvedKappa), and E_q[log q] = kappa A(kappa) - log(2 pi I0(kappa))
// in closed form.
struct VonMisesFitOptions {
  double lambda = 1e-4;     // the lambda of lambda kappa^2
  int max_iterations = 2000;
};

struct VonMisesFit {
  double mu = 0.0;     // radians, in [0, 2pi)
  double kappa = 0.0;
  double objective = 0.0;  // D at (mu, kappa)
  int iterations = 0;
};

// The largest kappa whose q still spans about eight bins of n (standard
// deviation 1/sqrt(kappa) = 4 bin widths); the fit keeps kappa below it.
double MaxResolvedKappa(int bins);

// D(mu, kappa) as above.
double ReverseKl(const std::vector<double>& log_p, double mu, double kappa, double lambda);

// The supplement's gradients of D:
//   dD/dmu    = -kappa E_q[sin(x - mu) log p]                          (Eq. 1)
//   dD/dkappa = kappa - A - kappa A^2 - E_q[(cos(x - mu) - A) log p]
//               + 2 lambda kappa                                        (Eq. 2)
void ReverseKlGradient(const std::vector<double>& log_p, double mu, double kappa, double lambda,
                       double* d_mu, double* d_kappa);

// Gradient descent, Eqs. 3-4: mu <- mu - a_mu dD/dmu, kappa <- kappa -
// a_kappa dD/dkappa, from (mu0, kappa0). The two rates follow the curvature
// of D, which near a lobe of concentration kappa is about kappa in mu and
// 1/(2 kappa^2) in kappa: a_mu = eta / kappa, a_kappa = eta kappa^2, with one
// step size eta that grows by 1.25 after an accepted step and halves (the
// step retried) when D would rise. D never increases; the fit stops when a
// step changes D by less than 1e-13 (relative), when eta underflows, or after
// max_iterations.
VonMisesFit FitVonMises(const std::vector<double>& log_p, double mu0, double kappa0,
                        const VonMisesFitOptions& options);

}  // namespace alignset

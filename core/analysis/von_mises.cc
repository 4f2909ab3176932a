#include "core/analysis/von_mises.h"

#include <algorithm>
#include <cmath>

#include "core/util/angles.h"

namespace alignset {
namespace {

// e^-k sqrt(2 pi k) I_nu(k) by the Hankel series
//   sum_m (-1)^m a_m(nu) / k^m,  a_m = prod_{j<=m} (4 nu^2 - (2j-1)^2) / (m! 8^m),
// summed while its terms shrink (k >= 30: they shrink to below 1e-20 first).
double ScaledHankel(int nu, double k) {
  const double mu4 = 4.0 * nu * nu;
  double term = 1.0, sum = 1.0;
  for (int m = 1; m < 200; ++m) {
    const double odd = 2.0 * m - 1.0;
    const double next = -term * (mu4 - odd * odd) / (8.0 * m * k);
    if (std::fabs(next) >= std::fabs(term)) break;  // the asymptotic series turns
    term = next;
    sum += term;
    if (std::fabs(term) < 1e-17 * std::fabs(sum)) break;
  }
  return sum;
}

}  // namespace

double LogBesselI0(double kappa) {
  if (kappa < kBesselSwitch) return std::log(std::cyl_bessel_i(0.0, kappa));
  return kappa - 0.5 * std::log(2.0 * kPi * kappa) + std::log(ScaledHankel(0, kappa));
}

double BesselRatio(double kappa) {
  if (kappa <= 0.0) return 0.0;
  if (kappa < kBesselSwitch) return std::cyl_bessel_i(1.0, kappa) / std::cyl_bessel_i(0.0, kappa);
  return ScaledHankel(1, kappa) / ScaledHankel(0, kappa);
}

double MaxResolvedKappa(int bins) {
  const double width = 2.0 * kPi / bins;
  return 1.0 / (16.0 * width * width);
}

namespace {

// cos and sin of the bin centres, so that cos(x - mu) = cos x cos mu +
// sin x sin mu needs no trigonometry per bin (the fit evaluates D a few
// hundred times).
struct Bins {
  explicit Bins(int n) : dx(2.0 * kPi / n), c(n), s(n) {
    for (int i = 0; i < n; ++i) {
      c[i] = std::cos((i + 0.5) * dx);
      s[i] = std::sin((i + 0.5) * dx);
    }
  }
  double dx;
  std::vector<double> c, s;
};

// q at the bin centres, normalised in closed form; also cos(x - mu) and
// sin(x - mu) there.
void Density(const Bins& b, double mu, double kappa, std::vector<double>* q,
             std::vector<double>* cos_d, std::vector<double>* sin_d) {
  const size_t n = b.c.size();
  const double cm = std::cos(mu), sm = std::sin(mu);
  // log q = kappa (cos - 1) - log(2 pi e^-kappa I0(kappa)): no overflow.
  const double log_norm = std::log(2.0 * kPi) + LogBesselI0(kappa) - kappa;
  q->resize(n);
  cos_d->resize(n);
  sin_d->resize(n);
  for (size_t i = 0; i < n; ++i) {
    const double cd = b.c[i] * cm + b.s[i] * sm;
    (*cos_d)[i] = cd;
    (*sin_d)[i] = b.s[i] * cm - b.c[i] * sm;
    (*q)[i] = std::exp(kappa * (cd - 1.0) - log_norm);
  }
}

double Objective(const Bins& b, const std::vector<double>& log_p, double mu, double kappa,
                 double lambda) {
  std::vector<double> q, cd, sd;
  Density(b, mu, kappa, &q, &cd, &sd);
  double e_log_p = 0.0;
  for (size_t i = 0; i < q.size(); ++i) e_log_p += q[i] * log_p[i];
  e_log_p *= b.dx;
  const double e_log_q = kappa * BesselRatio(kappa) - std::log(2.0 * kPi) - LogBesselI0(kappa);
  return e_log_q - e_log_p + lambda * kappa * kappa;
}

void Gradient(const Bins& b, const std::vector<double>& log_p, double mu, double kappa,
              double lambda, double* d_mu, double* d_kappa) {
  std::vector<double> q, cd, sd;
  Density(b, mu, kappa, &q, &cd, &sd);
  const double a = BesselRatio(kappa);
  double e_sin = 0.0, e_cos = 0.0;
  for (size_t i = 0; i < q.size(); ++i) {
    e_sin += q[i] * sd[i] * log_p[i];
    e_cos += q[i] * (cd[i] - a) * log_p[i];
  }
  *d_mu = -kappa * e_sin * b.dx;
  *d_kappa = kappa - a - kappa * a * a - e_cos * b.dx + 2.0 * lambda * kappa;
}

}  // namespace

double ReverseKl(const std::vector<double>& log_p, double mu, double kappa, double lambda) {
  return Objective(Bins(static_cast<int>(log_p.size())), log_p, mu, kappa, lambda);
}

void ReverseKlGradient(const std::vector<double>& log_p, double mu, double kappa, double lambda,
                       double* d_mu, double* d_kappa) {
  Gradient(Bins(static_cast<int>(log_p.size())), log_p, mu, kappa, lambda, d_mu, d_kappa);
}

VonMisesFit FitVonMises(const std::vector<double>& log_p, double mu0, double kappa0,
                        const VonMisesFitOptions& options) {
  const Bins bins(static_cast<int>(log_p.size()));
  const double kappa_max = MaxResolvedKappa(static_cast<int>(log_p.size()));
  constexpr double kKappaMin = 1e-3;
  VonMisesFit fit;
  fit.mu = mu0;
  fit.kappa = std::clamp(kappa0, kKappaMin, kappa_max);
  fit.objective = Objective(bins, log_p, fit.mu, fit.kappa, options.lambda);
  double eta = 0.1;
  for (int it = 0; it < options.max_iterations; ++it) {
    double gm = 0.0, gk = 0.0;
    Gradient(bins, log_p, fit.mu, fit.kappa, options.lambda, &gm, &gk);
    bool accepted = false;
    double mu = fit.mu, kappa = fit.kappa, objective = fit.objective;
    while (eta > 1e-14) {
      const double a_mu = eta / std::max(fit.kappa, 1.0);  // Eq. 3's alpha_mu
      const double a_kappa = eta * fit.kappa * fit.kappa;  // Eq. 4's alpha_kappa
      mu = fit.mu - a_mu * gm;
      kappa = std::clamp(fit.kappa - a_kappa * gk, kKappaMin, kappa_max);
      objective = Objective(bins, log_p, mu, kappa, options.lambda);
      if (objective <= fit.objective) {
        accepted = true;
        break;
      }
      eta *= 0.5;
    }
    fit.iterations = it + 1;
    if (!accepted) break;
    const double change = fit.objective - objective;
    fit.mu = mu;
    fit.kappa = kappa;
    fit.objective = objective;
    eta = std::min(eta * 1.25, 1e3);
    if (change <= 1e-13 * std::max(1.0, std::fabs(objective))) break;
  }
  fit.mu = std::fmod(fit.mu, 2.0 * kPi);
  if (fit.mu < 0.0) fit.mu += 2.0 * kPi;
  return fit;
}

}  // namespace alignset

#pragma once

#include <vector>

namespace alignset {

// The normalized 1-D Gaussian of standard deviation `sigma` (in pixels),
// truncated at ceil(3 sigma) and folded onto a ring of `period` pixels:
// entry d is the weight at offsets d, d +- period, ... sigma <= 0 gives the
// identity (a single 1 at offset 0).
std::vector<double> PeriodicGaussianKernel(double sigma, int period);

// The circular autocorrelation of a ring kernel: K[d] = sum_m k[m] k[m + d].
// Blurring by k and taking squared norms is the quadratic form of K:
// ||k * e||^2 = sum_{p,q} e_p K(p - q) e_q (K separable in 2-D).
std::vector<double> RingAutocorrelation(const std::vector<double>& k);

// Circular convolution of a W x H image (row-major, y * W + x) with the
// separable kernel kx (length W) along x and ky (length H) along y.
std::vector<double> PeriodicSeparableConvolve(const std::vector<double>& image, int w, int h,
                                              const std::vector<double>& kx,
                                              const std::vector<double>& ky);

// The image blurred by the Gaussian of `sigma` pixels, periodic at the
// borders (the seed 003 blur criterion's k_sigma).
std::vector<double> PeriodicGaussianBlur(const std::vector<double>& image, int w, int h,
                                         double sigma);

}  // namespace alignset

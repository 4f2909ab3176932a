#include "core/nufft_grid.h"

#include <fftw3.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <mutex>
#include <type_traits>

namespace alignset {
namespace {

// FFTW's planner keeps global state; every plan is made and destroyed under
// this lock so that engines in different threads can be set up at once.
std::mutex& FftwPlannerLock() {
  static std::mutex mu;
  return mu;
}

// Slabs per grid at most: enough to balance any thread count in use here.
constexpr int kMaxSlabs = 256;

// Calls f(std::integral_constant<int, W>) for the runtime width w, so the
// inner loops are compiled for each width and fully unrolled.
template <typename F>
void DispatchWidth(int w, F&& f) {
  switch (w) {
    case 2: return f(std::integral_constant<int, 2>{});
    case 3: return f(std::integral_constant<int, 3>{});
    case 4: return f(std::integral_constant<int, 4>{});
    case 5: return f(std::integral_constant<int, 5>{});
    case 6: return f(std::integral_constant<int, 6>{});
    case 7: return f(std::integral_constant<int, 7>{});
    case 8: return f(std::integral_constant<int, 8>{});
    case 9: return f(std::integral_constant<int, 9>{});
    case 10: return f(std::integral_constant<int, 10>{});
    case 11: return f(std::integral_constant<int, 11>{});
    case 12: return f(std::integral_constant<int, 12>{});
    case 13: return f(std::integral_constant<int, 13>{});
    case 14: return f(std::integral_constant<int, 14>{});
    case 15: return f(std::integral_constant<int, 15>{});
    default: return f(std::integral_constant<int, 16>{});
  }
}
static_assert(EsKernel::kMaxWidth == 16, "DispatchWidth covers widths 2..16");

inline int WrapIndex(int64_t i, int n) {
  int64_t r = i % n;
  return static_cast<int>(r < 0 ? r + n : r);
}

}  // namespace

int FastFftSize(int min_size) {
  // All 7-smooth numbers up to 2^30, sorted, built once (a few thousand).
  static const std::vector<int> sizes = [] {
    constexpr int64_t kLimit = int64_t{1} << 30;
    std::vector<int> v;
    for (int64_t a = 1; a <= kLimit; a *= 2) {
      for (int64_t b = a; b <= kLimit; b *= 3) {
        for (int64_t c = b; c <= kLimit; c *= 5) {
          for (int64_t d = c; d <= kLimit; d *= 7) v.push_back(static_cast<int>(d));
        }
      }
    }
    std::sort(v.begin(), v.end());
    return v;
  }();
  const auto it = std::lower_bound(sizes.begin(), sizes.end(), std::max(min_size, 1));
  return it == sizes.end() ? std::max(min_size, 1) : *it;
}

int NufftGridSize(int64_t m, const EsKernel& kernel) {
  const int64_t modes = 2 * m + 1;
  return FastFftSize(static_cast<int>(
      std::max<int64_t>(EsKernel::kOversampling * modes, 2 * kernel.width())));
}

NufftGrid::NufftGrid(const BasisBox& box, const EsKernel& kernel)
    : box_(box), kernel_(kernel), width_(kernel.width()) {
  n1_ = NufftGridSize(box.m1, kernel);
  n2_ = NufftGridSize(box.m2, kernel);
  stride_ = n2_ + width_ - 1;
  // Slab heights are at least one kernel width (n1 >= 2 width), and the
  // count is even so that even and odd slabs alternate around the torus.
  slabs_ = 2 * std::max(1, std::min(n1_ / (2 * width_), kMaxSlabs / 2));
  const std::vector<double> phi1 = kernel.FourierTransform(n1_, static_cast<int>(box.m1));
  const std::vector<double> phi2 = kernel.FourierTransform(n2_, static_cast<int>(box.m2));
  for (double v : phi1) inv_phi_hat1_.push_back(1.0 / v);
  for (double v : phi2) inv_phi_hat2_.push_back(1.0 / v);

  spread_.assign(static_cast<size_t>(n1_) * stride_, 0.0);
  gather_.assign(static_cast<size_t>(n1_) * stride_, 0.0);
  const size_t cells = static_cast<size_t>(n1_) * n2_;
  const size_t half = static_cast<size_t>(n1_) * (n2_ / 2 + 1);
  fft_real_ = static_cast<double*>(fftw_malloc(sizeof(double) * cells));
  fft_half_ = static_cast<std::complex<double>*>(fftw_malloc(sizeof(fftw_complex) * half));
  fft_full_ = static_cast<std::complex<double>*>(fftw_malloc(sizeof(fftw_complex) * cells));
  std::lock_guard<std::mutex> lock(FftwPlannerLock());
  // FFTW_ESTIMATE: planning does not time anything, so the same sizes give
  // the same algorithm (and the same bits) on every run.
  plan_r2c_ = fftw_plan_dft_r2c_2d(n1_, n2_, fft_real_,
                                   reinterpret_cast<fftw_complex*>(fft_half_), FFTW_ESTIMATE);
  plan_c2c_ = fftw_plan_dft_2d(n1_, n2_, reinterpret_cast<fftw_complex*>(fft_full_),
                               reinterpret_cast<fftw_complex*>(fft_full_), FFTW_FORWARD,
                               FFTW_ESTIMATE);
}

NufftGrid::~NufftGrid() {
  {
    std::lock_guard<std::mutex> lock(FftwPlannerLock());
    fftw_destroy_plan(static_cast<fftw_plan>(plan_r2c_));
    fftw_destroy_plan(static_cast<fftw_plan>(plan_c2c_));
  }
  fftw_free(fft_real_);
  fftw_free(fft_half_);
  fftw_free(fft_full_);
}

void NufftGrid::Prepare(const PointSet& points, bool keep_weights, ThreadPool& pool) {
  count_ = points.size();
  const LatticeBasis& b = box_.basis;
  const double p1 = static_cast<double>(b.p1), p2 = static_cast<double>(b.p2);
  const double q1 = static_cast<double>(b.q1), q2 = static_cast<double>(b.q2);
  std::vector<double>& x1 = scratch1_;
  std::vector<double>& x2 = scratch2_;
  x1.resize(count_);
  x2.resize(count_);
  slab_of_.resize(count_);
  pool.ParallelFor(count_, [&](size_t begin, size_t end, int) {
    for (size_t j = begin; j < end; ++j) {
      const Point2& s = points[j];
      const double u1 = Wrap01(p1 * s.x + p2 * s.y);
      const double u2 = Wrap01(q1 * s.x + q2 * s.y);
      x1[j] = u1 * n1_;
      x2[j] = u2 * n2_;
      const int row = WrapIndex(static_cast<int64_t>(std::ceil(x1[j] - 0.5 * width_)), n1_);
      slab_of_[j] = static_cast<uint16_t>(static_cast<int64_t>(row) * slabs_ / n1_);
    }
  });
  // Stable counting sort into slabs.
  slab_start_.assign(slabs_ + 1, 0);
  for (size_t j = 0; j < count_; ++j) ++slab_start_[slab_of_[j] + 1];
  for (int s = 0; s < slabs_; ++s) slab_start_[s + 1] += slab_start_[s];
  std::vector<size_t> next(slab_start_.begin(), slab_start_.end() - 1);
  order_.resize(count_);
  x1_.resize(count_);
  x2_.resize(count_);
  for (size_t j = 0; j < count_; ++j) {
    const size_t pos = next[slab_of_[j]]++;
    order_[pos] = static_cast<uint32_t>(j);
    x1_[pos] = x1[j];
    x2_[pos] = x2[j];
  }
  weights_kept_ = false;
  if (!keep_weights) {
    k1_.clear();
    k2_.clear();
    row_.clear();
    col_.clear();
    return;
  }
  const size_t w = static_cast<size_t>(width_);
  k1_.resize(count_ * w);
  k2_.resize(count_ * w);
  row_.resize(count_);
  col_.resize(count_);
  DispatchWidth(width_, [&](auto wc) {
    constexpr int W = decltype(wc)::value;
    pool.ParallelFor(count_, [&](size_t begin, size_t end, int) {
      for (size_t pos = begin; pos < end; ++pos) {
        WeightsAt<W>(pos, &k1_[pos * W], &k2_[pos * W], &row_[pos], &col_[pos]);
      }
    });
  });
  weights_kept_ = true;
}

template <int W>
void NufftGrid::WeightsAt(size_t pos, double* k1, double* k2, int* row, int* col) const {
  *row = WrapIndex(kernel_.Weights<W>(x1_[pos], k1), n1_);
  *col = WrapIndex(kernel_.Weights<W>(x2_[pos], k2), n2_);
}

void NufftGrid::Spread(ThreadPool& pool) {
  std::fill(spread_.begin(), spread_.end(), 0.0);
  DispatchWidth(width_, [&](auto wc) { SpreadSlabs<decltype(wc)::value>(pool); });
  // Fold the padding columns back onto the first ones (periodic in w2).
  const int w = width_;
  pool.ParallelFor(static_cast<size_t>(n1_), [&](size_t begin, size_t end, int) {
    for (size_t r = begin; r < end; ++r) {
      const double* g = &spread_[r * stride_];
      double* dst = &fft_real_[r * n2_];
      std::memcpy(dst, g, sizeof(double) * n2_);
      for (int c = 0; c < w - 1; ++c) dst[c] += g[n2_ + c];
    }
  });
}

template <int W>
void NufftGrid::SpreadSlabs(ThreadPool& pool) {
  constexpr int w = W;
  for (int parity = 0; parity < 2; ++parity) {
    const size_t jobs = static_cast<size_t>(slabs_ / 2);
    pool.ParallelFor(jobs, [&](size_t begin, size_t end, int) {
      double k1_buf[W], k2_buf[W];
      for (size_t job = begin; job < end; ++job) {
        const size_t slab = 2 * job + parity;
        for (size_t pos = slab_start_[slab]; pos < slab_start_[slab + 1]; ++pos) {
          const double* k1;
          const double* k2;
          int row, col;
          if (weights_kept_) {
            k1 = &k1_[pos * w];
            k2 = &k2_[pos * w];
            row = row_[pos];
            col = col_[pos];
          } else {
            WeightsAt<W>(pos, k1_buf, k2_buf, &row, &col);
            k1 = k1_buf;
            k2 = k2_buf;
          }
          for (int t1 = 0; t1 < w; ++t1) {
            int r = row + t1;
            if (r >= n1_) r -= n1_;
            double* g = &spread_[static_cast<size_t>(r) * stride_ + col];
            const double a = k1[t1];
            for (int t2 = 0; t2 < w; ++t2) g[t2] += a * k2[t2];
          }
        }
      }
    });
  }
}

void NufftGrid::TransformSpread() {
  fftw_execute(static_cast<fftw_plan>(plan_r2c_));
}

std::complex<double> NufftGrid::Mode(int64_t w1, int64_t w2) const {
  const double corr = inv_phi_hat1_[static_cast<size_t>(std::abs(w1))] *
                      inv_phi_hat2_[static_cast<size_t>(std::abs(w2))];
  // The spread strengths are real: the half spectrum holds w2 >= 0, and
  // F(-w) = conj F(w) gives the rest.
  if (w2 >= 0) {
    return corr * fft_half_[static_cast<size_t>(WrapIndex(w1, n1_)) * (n2_ / 2 + 1) +
                            static_cast<size_t>(w2)];
  }
  return corr * std::conj(fft_half_[static_cast<size_t>(WrapIndex(-w1, n1_)) * (n2_ / 2 + 1) +
                                    static_cast<size_t>(-w2)]);
}

void NufftGrid::ClearCoefficients() {
  std::fill(fft_full_, fft_full_ + static_cast<size_t>(n1_) * n2_, std::complex<double>(0.0));
}

void NufftGrid::AddCoefficient(int64_t w1, int64_t w2, std::complex<double> c) {
  const double corr = inv_phi_hat1_[static_cast<size_t>(std::abs(w1))] *
                      inv_phi_hat2_[static_cast<size_t>(std::abs(w2))];
  fft_full_[static_cast<size_t>(WrapIndex(w1, n1_)) * n2_ + WrapIndex(w2, n2_)] += corr * c;
}

void NufftGrid::TransformCoefficients() {
  fftw_execute(static_cast<fftw_plan>(plan_c2c_));
  // Padded copy: columns n2 .. n2 + width - 2 repeat the first ones, so the
  // interpolation reads each row without wrapping.
  for (int r = 0; r < n1_; ++r) {
    const std::complex<double>* src = &fft_full_[static_cast<size_t>(r) * n2_];
    std::complex<double>* dst = &gather_[static_cast<size_t>(r) * stride_];
    std::copy(src, src + n2_, dst);
    std::copy(src, src + (width_ - 1), dst + n2_);
  }
}

void NufftGrid::Interpolate(ThreadPool& pool, std::complex<double>* out) const {
  DispatchWidth(width_, [&](auto wc) { InterpolatePoints<decltype(wc)::value>(pool, out); });
}

template <int W>
void NufftGrid::InterpolatePoints(ThreadPool& pool, std::complex<double>* out) const {
  constexpr int w = W;
  const double* grid = reinterpret_cast<const double*>(gather_.data());
  pool.ParallelFor(count_, [&](size_t begin, size_t end, int) {
    double k1_buf[W], k2_buf[W];
    for (size_t pos = begin; pos < end; ++pos) {
      const double* k1;
      const double* k2;
      int row, col;
      if (weights_kept_) {
        k1 = &k1_[pos * w];
        k2 = &k2_[pos * w];
        row = row_[pos];
        col = col_[pos];
      } else {
        WeightsAt<W>(pos, k1_buf, k2_buf, &row, &col);
        k1 = k1_buf;
        k2 = k2_buf;
      }
      double re = 0.0, im = 0.0;
      for (int t1 = 0; t1 < w; ++t1) {
        int r = row + t1;
        if (r >= n1_) r -= n1_;
        const double* g = grid + 2 * (static_cast<size_t>(r) * stride_ + col);
        double sr = 0.0, si = 0.0;
        for (int t2 = 0; t2 < w; ++t2) {
          sr += k2[t2] * g[2 * t2];
          si += k2[t2] * g[2 * t2 + 1];
        }
        re += k1[t1] * sr;
        im += k1[t1] * si;
      }
      out[order_[pos]] += std::complex<double>(re, im);
    }
  });
}

}  // namespace alignset

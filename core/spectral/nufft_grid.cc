#include "core/spectral/nufft_grid.h"

#include <fftw3.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <mutex>

#include "core/spectral/fftw_planner_lock.h"

namespace alignset {
namespace {

// Slabs per grid at most: enough to balance any thread count in use here.
constexpr int kMaxSlabs = 256;

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
    : box_(box), kernel_(kernel), loops_(SelectedNufftLoops()), width_(kernel.width()) {
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

  spread_.assign(static_cast<size_t>(n1_ + width_ - 1) * stride_, 0.0);
  gather_.assign(static_cast<size_t>(n1_ + width_ - 1) * stride_, 0.0);
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

void NufftGrid::Resize(size_t count, bool keep_weights) {
  count_ = count;
  keep_weights_ = keep_weights;
  mapped1_.resize(count);
  mapped2_.resize(count);
  slab_of_.resize(count);
  order_.resize(count);
  x1_.resize(count);
  x2_.resize(count);
  const size_t kept = keep_weights ? count : 0;
  k1_.resize(kept * width_);
  k2_.resize(kept * width_);
  row_.resize(kept);
  col_.resize(kept);
}

void NufftGrid::MapPoints(const PointSet& points, size_t begin, size_t end) {
  const LatticeBasis& b = box_.basis;
  const double p1 = static_cast<double>(b.p1), p2 = static_cast<double>(b.p2);
  const double q1 = static_cast<double>(b.q1), q2 = static_cast<double>(b.q2);
  for (size_t j = begin; j < end; ++j) {
    const Point2& s = points[j];
    const double x1 = Wrap01(p1 * s.x + p2 * s.y) * n1_;
    mapped1_[j] = x1;
    mapped2_[j] = Wrap01(q1 * s.x + q2 * s.y) * n2_;
    const int row = WrapIndex(static_cast<int64_t>(std::ceil(x1 - 0.5 * width_)), n1_);
    slab_of_[j] = static_cast<uint16_t>(static_cast<int64_t>(row) * slabs_ / n1_);
  }
}

void NufftGrid::SortIntoSlabs() {
  slab_start_.assign(slabs_ + 1, 0);
  for (size_t j = 0; j < count_; ++j) ++slab_start_[slab_of_[j] + 1];
  for (int s = 0; s < slabs_; ++s) slab_start_[s + 1] += slab_start_[s];
  std::vector<size_t> next(slab_start_.begin(), slab_start_.end() - 1);
  for (size_t j = 0; j < count_; ++j) {
    const size_t pos = next[slab_of_[j]]++;
    order_[pos] = static_cast<uint32_t>(j);
    x1_[pos] = mapped1_[j];
    x2_[pos] = mapped2_[j];
  }
  std::fill(spread_.begin(), spread_.end(), 0.0);
}

void NufftGrid::ComputeWeights(size_t begin, size_t end) {
  if (begin >= end) return;
  const size_t w = static_cast<size_t>(width_);
  loops_.weights(kernel_.coefficients(), kernel_.degree(), width_, &x1_[begin], end - begin, n1_,
                 &k1_[begin * w], &row_[begin]);
  loops_.weights(kernel_.coefficients(), kernel_.degree(), width_, &x2_[begin], end - begin, n2_,
                 &k2_[begin * w], &col_[begin]);
  if (strengths_ != nullptr) ApplyStrengths(begin, end, &k1_[begin * w]);
}

void NufftGrid::ApplyStrengths(size_t begin, size_t end, double* k1) const {
  const size_t w = static_cast<size_t>(width_);
  for (size_t pos = begin; pos < end; ++pos) {
    const double f = strengths_[order_[pos]];
    double* row = k1 + (pos - begin) * w;
    for (size_t t = 0; t < w; ++t) row[t] *= f;
  }
}

void NufftGrid::BlockWeights(size_t begin, size_t end, Scratch* scratch) const {
  const size_t w = static_cast<size_t>(width_);
  scratch->k1.resize(kScratchBlock * w);
  scratch->k2.resize(kScratchBlock * w);
  scratch->row.resize(kScratchBlock);
  scratch->col.resize(kScratchBlock);
  loops_.weights(kernel_.coefficients(), kernel_.degree(), width_, &x1_[begin], end - begin, n1_,
                 scratch->k1.data(), scratch->row.data());
  loops_.weights(kernel_.coefficients(), kernel_.degree(), width_, &x2_[begin], end - begin, n2_,
                 scratch->k2.data(), scratch->col.data());
}

void NufftGrid::SpreadRange(size_t begin, size_t end, Scratch* scratch) {
  if (begin >= end) return;
  const size_t w = static_cast<size_t>(width_);
  if (keep_weights_) {
    loops_.spread(spread_.data(), stride_, width_, &k1_[begin * w], &k2_[begin * w],
                  &row_[begin], &col_[begin], end - begin);
    return;
  }
  for (size_t b = begin; b < end; b += kScratchBlock) {
    const size_t e = std::min(end, b + kScratchBlock);
    BlockWeights(b, e, scratch);
    if (strengths_ != nullptr) ApplyStrengths(b, e, scratch->k1.data());
    loops_.spread(spread_.data(), stride_, width_, scratch->k1.data(), scratch->k2.data(),
                  scratch->row.data(), scratch->col.data(), e - b);
  }
}

void NufftGrid::FinishSpread() {
  // Fold the padding rows, then the padding columns, back onto the first
  // ones (the grid is periodic).
  for (int r = n1_; r < n1_ + width_ - 1; ++r) {
    const double* src = &spread_[static_cast<size_t>(r) * stride_];
    double* dst = &spread_[static_cast<size_t>(r - n1_) * stride_];
    for (int c = 0; c < stride_; ++c) dst[c] += src[c];
  }
  for (int r = 0; r < n1_; ++r) {
    const double* g = &spread_[static_cast<size_t>(r) * stride_];
    double* dst = &fft_real_[static_cast<size_t>(r) * n2_];
    std::memcpy(dst, g, sizeof(double) * n2_);
    for (int c = 0; c < width_ - 1; ++c) dst[c] += g[n2_ + c];
  }
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

void NufftGrid::FinishCoefficients() {
  fftw_execute(static_cast<fftw_plan>(plan_c2c_));
  // Padded copy: rows n1 .. n1 + width - 2 and columns n2 .. n2 + width - 2
  // repeat the first ones, so the interpolation never wraps.
  for (int r = 0; r < n1_ + width_ - 1; ++r) {
    const std::complex<double>* src = &fft_full_[static_cast<size_t>(r % n1_) * n2_];
    std::complex<double>* dst = &gather_[static_cast<size_t>(r) * stride_];
    std::copy(src, src + n2_, dst);
    std::copy(src, src + (width_ - 1), dst + n2_);
  }
}

void NufftGrid::InterpolateRange(size_t begin, size_t end, std::complex<double>* by_point,
                                 Scratch* scratch) const {
  const size_t w = static_cast<size_t>(width_);
  std::complex<double> values[kScratchBlock];
  for (size_t b = begin; b < end; b += kScratchBlock) {
    const size_t e = std::min(end, b + kScratchBlock);
    if (keep_weights_) {
      loops_.interpolate(gather_.data(), stride_, width_, &k1_[b * w], &k2_[b * w], &row_[b],
                         &col_[b], e - b, values);
    } else {
      BlockWeights(b, e, scratch);
      loops_.interpolate(gather_.data(), stride_, width_, scratch->k1.data(),
                         scratch->k2.data(), scratch->row.data(), scratch->col.data(), e - b,
                         values);
    }
    for (size_t pos = b; pos < e; ++pos) by_point[order_[pos]] = values[pos - b];
  }
}

}  // namespace alignset

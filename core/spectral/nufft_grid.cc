#include "core/spectral/nufft_grid.h"

#include <fftw3.h>

#include <algorithm>
#include <cmath>
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
  m2_ = static_cast<int>(box.m2);
  coef_width_ = 2 * m2_ + 1;
  const size_t half = static_cast<size_t>(n1_) * (n2_ / 2 + 1);
  fft_half_ = static_cast<std::complex<double>*>(fftw_malloc(sizeof(fftw_complex) * half));
  coef_ = static_cast<std::complex<double>*>(
      fftw_malloc(sizeof(fftw_complex) * static_cast<size_t>(n1_) * coef_width_));
  std::fill(coef_, coef_ + static_cast<size_t>(n1_) * coef_width_, std::complex<double>(0.0));
  mid_ = static_cast<std::complex<double>*>(
      fftw_malloc(sizeof(fftw_complex) * static_cast<size_t>(n1_) * n2_));
  std::fill(mid_, mid_ + static_cast<size_t>(n1_) * n2_, std::complex<double>(0.0));
  auto c = [](std::complex<double>* p) { return reinterpret_cast<fftw_complex*>(p); };
  const int h = n2_ / 2 + 1;
  std::lock_guard<std::mutex> lock(FftwPlannerLock());
  // FFTW_ESTIMATE: planning does not time anything, so the same sizes give
  // the same algorithm (and the same bits) on every run.
  //
  // The 2-D transforms are pruned to the box: the modes read after a type-1
  // pass are the columns w2 in [0, m2] of the half spectrum, and the
  // coefficients of a type-2 pass fill only the columns |w2| <= m2, so one
  // of the two 1-D passes of each runs on about half the columns (the grid
  // is oversampled twice). Type 1: the rows of the padded spreading grid
  // (stride apart), real to half complex, then the kept columns in place.
  plan_rows_r2c_ = fftw_plan_many_dft_r2c(1, &n2_, n1_, spread_.data(), nullptr, 1, stride_,
                                          c(fft_half_), nullptr, 1, h, FFTW_ESTIMATE);
  plan_cols_half_ = fftw_plan_many_dft(1, &n1_, m2_ + 1, c(fft_half_), nullptr, h, 1,
                                       c(fft_half_), nullptr, h, 1, FFTW_FORWARD, FFTW_ESTIMATE);
  // Type 2: the coefficient columns w2 = 0..m2 and -m2..-1 (stored at
  // w2 + m2) into the grid's columns 0..m2 and n2 - m2..n2 - 1, then every
  // row into the padded interpolation grid. Both out of place with the
  // input kept, so the columns outside the box stay zero and the
  // coefficients can be cleared where they were written.
  const unsigned keep = FFTW_ESTIMATE | FFTW_PRESERVE_INPUT;
  plan_cols_pos_ = fftw_plan_many_dft(1, &n1_, m2_ + 1, c(coef_ + m2_), nullptr, coef_width_, 1,
                                      c(mid_), nullptr, n2_, 1, FFTW_FORWARD, keep);
  plan_cols_neg_ =
      m2_ > 0 ? fftw_plan_many_dft(1, &n1_, m2_, c(coef_), nullptr, coef_width_, 1,
                                   c(mid_ + (n2_ - m2_)), nullptr, n2_, 1, FFTW_FORWARD, keep)
              : nullptr;
  plan_rows_c2c_ = fftw_plan_many_dft(1, &n2_, n1_, c(mid_), nullptr, 1, n2_, c(gather_.data()),
                                      nullptr, 1, stride_, FFTW_FORWARD, keep);
}

NufftGrid::~NufftGrid() {
  {
    std::lock_guard<std::mutex> lock(FftwPlannerLock());
    for (void* plan :
         {plan_rows_r2c_, plan_cols_half_, plan_cols_pos_, plan_cols_neg_, plan_rows_c2c_}) {
      if (plan != nullptr) fftw_destroy_plan(static_cast<fftw_plan>(plan));
    }
  }
  fftw_free(fft_half_);
  fftw_free(coef_);
  fftw_free(mid_);
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
    double* g = &spread_[static_cast<size_t>(r) * stride_];
    for (int c = 0; c < width_ - 1; ++c) g[c] += g[n2_ + c];
  }
  fftw_execute(static_cast<fftw_plan>(plan_rows_r2c_));
  fftw_execute(static_cast<fftw_plan>(plan_cols_half_));
}

void NufftGrid::BindModes(const std::vector<int32_t>& w1, const std::vector<int32_t>& w2) {
  const size_t count = w1.size();
  const size_t half = static_cast<size_t>(n2_ / 2 + 1);
  corr_.resize(count);
  mode_cell_.resize(count);
  mode_conj_.resize(count);
  coef_plus_.resize(count);
  coef_minus_.resize(count);
  auto coef_cell = [&](int64_t a, int64_t b) {
    return static_cast<size_t>(WrapIndex(a, n1_)) * coef_width_ + static_cast<size_t>(b + m2_);
  };
  for (size_t i = 0; i < count; ++i) {
    corr_[i] = inv_phi_hat1_[static_cast<size_t>(std::abs(w1[i]))] *
               inv_phi_hat2_[static_cast<size_t>(std::abs(w2[i]))];
    // The spread strengths are real: the half spectrum holds w2 >= 0, and
    // F(-w) = conj F(w) gives the rest.
    mode_conj_[i] = w2[i] < 0;
    mode_cell_[i] = w2[i] >= 0
                        ? static_cast<size_t>(WrapIndex(w1[i], n1_)) * half +
                              static_cast<size_t>(w2[i])
                        : static_cast<size_t>(WrapIndex(-static_cast<int64_t>(w1[i]), n1_)) * half +
                              static_cast<size_t>(-w2[i]);
    coef_plus_[i] = coef_cell(w1[i], w2[i]);
    coef_minus_[i] = coef_cell(-static_cast<int64_t>(w1[i]), -static_cast<int64_t>(w2[i]));
  }
}

void NufftGrid::ClearCoefficients() {
  for (size_t cell : coef_plus_) coef_[cell] = 0.0;
  for (size_t cell : coef_minus_) coef_[cell] = 0.0;
}

void NufftGrid::FinishCoefficients() {
  fftw_execute(static_cast<fftw_plan>(plan_cols_pos_));
  if (plan_cols_neg_ != nullptr) fftw_execute(static_cast<fftw_plan>(plan_cols_neg_));
  fftw_execute(static_cast<fftw_plan>(plan_rows_c2c_));
  // Padding: columns n2 .. n2 + width - 2 and rows n1 .. n1 + width - 2
  // repeat the first ones, so the interpolation never wraps.
  for (int r = 0; r < n1_; ++r) {
    std::complex<double>* row = &gather_[static_cast<size_t>(r) * stride_];
    std::copy(row, row + (width_ - 1), row + n2_);
  }
  std::copy(gather_.begin(), gather_.begin() + static_cast<std::ptrdiff_t>(width_ - 1) * stride_,
            gather_.begin() + static_cast<std::ptrdiff_t>(n1_) * stride_);
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

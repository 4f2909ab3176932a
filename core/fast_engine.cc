#include "core/fast_engine.h"

#include <algorithm>
#include <cmath>

#include "core/angles.h"
#include "core/frequency_partition.h"

namespace alignset {

FastEngine::FastEngine(int threads, double tolerance) : pool_(threads), kernel_(tolerance) {}

FastEngine::~FastEngine() = default;

size_t FastEngine::grid_cells() const {
  size_t cells = 0;
  for (const Piece& p : grids_) cells += static_cast<size_t>(p.grid->n1()) * p.grid->n2();
  return cells;
}

void FastEngine::SetFrequencies(const std::vector<Frequency>& k) {
  k_ = k;
  grids_.clear();
  // Cost model of one piece, in rough nanoseconds: spreading and
  // interpolation (3 w^2 multiply-adds per point: one real, one complex
  // pass) plus 2 w kernel values per point, against the FFTs and the grid
  // sweeps. N is not known before Evaluate; |K| ~ N for the sets alignset
  // builds.
  const double n_proxy = static_cast<double>(std::max<size_t>(k.size(), 16));
  const double w = kernel_.width();
  const double per_piece = n_proxy * (3.0 * w * w + 20.0 * w);
  const EsKernel& kernel = kernel_;
  auto cost = [&](int64_t m1, int64_t m2) {
    const double cells = static_cast<double>(NufftGridSize(m1, kernel)) *
                         static_cast<double>(NufftGridSize(m2, kernel));
    return per_piece + cells * (2.5 * std::log2(cells) + 6.0);
  };
  std::vector<FrequencyPiece> pieces = PartitionFrequencies(k_, cost);
  for (FrequencyPiece& fp : pieces) {
    // Rows are the long axis: the spreading runs in parallel over slabs of
    // rows.
    if (fp.box.m2 > fp.box.m1) {
      fp.box = {fp.box.basis.Swapped(), fp.box.m2, fp.box.m1};
    }
    Piece piece;
    piece.grid = std::make_unique<NufftGrid>(fp.box, kernel_);
    piece.members = std::move(fp.members);
    for (uint32_t i : piece.members) {
      piece.w1.push_back(static_cast<int32_t>(fp.box.basis.W1(k_[i].a, k_[i].b)));
      piece.w2.push_back(static_cast<int32_t>(fp.box.basis.W2(k_[i].a, k_[i].b)));
    }
    grids_.push_back(std::move(piece));
  }
}

void FastEngine::Evaluate(const PointSet& points, bool with_gradient, SpectrumEvaluation* out) {
  const size_t n = points.size();
  const size_t nk = k_.size();
  out->spectrum.assign(nk, {0.0, 0.0});
  out->gradient.clear();
  if (with_gradient) out->gradient.assign(n, {0.0, 0.0});
  out->loss = 0.0;
  if (nk == 0 || n == 0) return;

  const size_t w = static_cast<size_t>(kernel_.width());
  const bool keep = n * grids_.size() * 2 * w * sizeof(double) <= kWeightBudgetBytes;
  for (Piece& p : grids_) p.grid->Prepare(points, keep, pool_);
  for (Piece& p : grids_) p.grid->Spread(pool_);
  pool_.ParallelFor(grids_.size(), [&](size_t begin, size_t end, int) {
    for (size_t g = begin; g < end; ++g) grids_[g].grid->TransformSpread();
  });
  for (const Piece& p : grids_) {
    pool_.ParallelFor(p.members.size(), [&](size_t begin, size_t end, int) {
      for (size_t i = begin; i < end; ++i) {
        out->spectrum[p.members[i]] = p.grid->Mode(p.w1[i], p.w2[i]);
      }
    });
  }
  double power = 0.0;
  for (const std::complex<double>& f : out->spectrum) power += std::norm(f);
  const double dn = static_cast<double>(n);
  out->loss = power / (dn * static_cast<double>(nk));
  if (!with_gradient) return;

  // Over K, sum_v v Im(conj(F_v) e_j(v)) = (1 / 2i) sum over +-K of
  // c(u) e_j(u) with c(u) = u conj(F(u)), F(-v) = conj F(v). Packing both
  // components as h(u) = (u_x + i u_y) conj(F(u)), the type-2 sum
  // T_j = sum over +-K of h(u) e_j(u) equals 2i X_j - 2 Y_j with X_j, Y_j
  // the real sums of the x and y components.
  pool_.ParallelFor(grids_.size(), [&](size_t begin, size_t end, int) {
    for (size_t g = begin; g < end; ++g) {
      Piece& p = grids_[g];
      p.grid->ClearCoefficients();
      for (size_t i = 0; i < p.members.size(); ++i) {
        const Frequency& v = k_[p.members[i]];
        const std::complex<double> f = out->spectrum[p.members[i]];
        const std::complex<double> dir(v.a, v.b);
        p.grid->AddCoefficient(p.w1[i], p.w2[i], dir * std::conj(f));
        p.grid->AddCoefficient(-p.w1[i], -p.w2[i], -dir * f);
      }
      p.grid->TransformCoefficients();
    }
  });
  sums_.resize(n);
  std::fill(sums_.begin(), sums_.end(), std::complex<double>(0.0));
  for (const Piece& p : grids_) p.grid->Interpolate(pool_, sums_.data());
  const double scale = 4.0 * kPi / (dn * static_cast<double>(nk));
  for (size_t j = 0; j < n; ++j) {
    out->gradient[j] = {0.5 * scale * sums_[j].imag(), -0.5 * scale * sums_[j].real()};
  }
}

}  // namespace alignset

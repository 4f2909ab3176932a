#include "core/spectral/fast_engine.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/util/angles.h"
#include "core/spectral/frequency_partition.h"

namespace alignset {

FastEngine::FastEngine(int threads, double tolerance, size_t weight_budget_bytes)
    : pool_(threads),
      kernel_(tolerance),
      weight_budget_bytes_(weight_budget_bytes),
      scratch_(static_cast<size_t>(pool_.size())) {}

FastEngine::~FastEngine() = default;

size_t FastEngine::grid_cells() const {
  size_t cells = 0;
  for (const Piece& p : grids_) cells += static_cast<size_t>(p.grid->n1()) * p.grid->n2();
  return cells;
}

void FastEngine::SetTolerance(double tolerance) {
  EsKernel kernel(tolerance);
  // The kernel is a function of its width alone (beta = 2.30 width).
  if (kernel.width() == kernel_.width()) return;
  kernel_ = std::move(kernel);
  // The grids hold the kernel's Fourier transform and width; K and the
  // weights stay.
  BuildGrids();
}

void FastEngine::SetLossWeights(std::vector<double> weights) { weights_ = std::move(weights); }

void FastEngine::SetFrequencies(const std::vector<Frequency>& k) {
  k_ = k;
  weights_.clear();
  BuildGrids();
}

void FastEngine::BuildGrids() {
  grids_.clear();
  grid_of_.assign(k_.size(), 0);
  local_of_.assign(k_.size(), 0);
  // Cost model of one piece, in rough nanoseconds: spreading and
  // interpolation (3 w^2 multiply-adds per point: one real, one complex
  // pass) plus 2 w kernel values per point, against the FFTs and the grid
  // sweeps. N is not known before Evaluate; |K| ~ N for the sets alignset
  // builds.
  const double n_proxy = static_cast<double>(std::max<size_t>(k_.size(), 16));
  const double w = kernel_.width();
  const double per_piece = n_proxy * (3.0 * w * w + 20.0 * w);
  const EsKernel& kernel = kernel_;
  // The partition prices many thousands of boxes over a few hundred
  // distinct extents: the grid size of each extent is looked up once.
  std::vector<int> grid_size;
  auto size_of = [&](int64_t m) {
    const size_t i = static_cast<size_t>(m);
    if (i >= grid_size.size()) grid_size.resize(std::max(i + 1, 2 * grid_size.size()), 0);
    if (grid_size[i] == 0) grid_size[i] = NufftGridSize(m, kernel);
    return grid_size[i];
  };
  auto cost = [&](int64_t m1, int64_t m2) {
    const double cells = static_cast<double>(size_of(m1)) * static_cast<double>(size_of(m2));
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
    // The members' modes in the grid's basis, bound to the grid once.
    std::vector<int32_t> w1, w2;
    for (uint32_t i : piece.members) {
      grid_of_[i] = static_cast<uint32_t>(grids_.size());
      local_of_[i] = static_cast<uint32_t>(w1.size());
      w1.push_back(static_cast<int32_t>(fp.box.basis.W1(k_[i].a, k_[i].b)));
      w2.push_back(static_cast<int32_t>(fp.box.basis.W2(k_[i].a, k_[i].b)));
    }
    piece.grid->BindModes(w1, w2);
    grids_.push_back(std::move(piece));
  }
}

void FastEngine::RunBalanced(const std::vector<size_t>& weights,
                             const std::function<void(size_t, int)>& fn) {
  std::vector<size_t> prefix(weights.size() + 1, 0);
  for (size_t j = 0; j < weights.size(); ++j) prefix[j + 1] = prefix[j] + weights[j];
  const size_t workers = static_cast<size_t>(pool_.size());
  pool_.ParallelFor(workers, [&](size_t begin, size_t end, int worker) {
    for (size_t w = begin; w < end; ++w) {
      // Jobs whose first unit of weight falls in this worker's share.
      const size_t lo = prefix.back() * w / workers, hi = prefix.back() * (w + 1) / workers;
      const size_t first = static_cast<size_t>(
          std::lower_bound(prefix.begin(), prefix.end() - 1, lo) - prefix.begin());
      const size_t last = w + 1 == workers
                              ? weights.size()
                              : static_cast<size_t>(std::lower_bound(prefix.begin(),
                                                                     prefix.end() - 1, hi) -
                                                    prefix.begin());
      for (size_t j = first; j < last; ++j) fn(j, worker);
    }
  });
}

void FastEngine::RunOverGrids(size_t count,
                              const std::function<void(size_t, size_t, size_t, int)>& fn) {
  pool_.ParallelFor(count * grids_.size(), [&](size_t begin, size_t end, int worker) {
    while (begin < end) {
      const size_t g = begin / count;
      const size_t local = begin - g * count;
      const size_t stop = std::min(end - g * count, count);
      fn(g, local, stop, worker);
      begin = g * count + stop;
    }
  });
}

void FastEngine::TypeOne(const PointSet& points, const double* strengths, bool keep_allowed,
                         std::vector<std::complex<double>>* spectrum) {
  const size_t n = points.size();
  const size_t nk = k_.size();
  // Every stage is one parallel loop across all grids.
  const size_t w = static_cast<size_t>(kernel_.width());
  const bool keep =
      keep_allowed && n * grids_.size() * 2 * w * sizeof(double) <= weight_budget_bytes_;
  for (Piece& p : grids_) {
    p.grid->Resize(n, keep);
    p.grid->SetStrengths(strengths);
  }
  pool_.ParallelFor(n, [&](size_t begin, size_t end, int) {
    for (Piece& p : grids_) p.grid->MapPoints(points, begin, end);
  });
  pool_.ParallelFor(grids_.size(), [&](size_t begin, size_t end, int) {
    for (size_t g = begin; g < end; ++g) grids_[g].grid->SortIntoSlabs();
  });
  if (keep) {
    RunOverGrids(n, [&](size_t g, size_t begin, size_t end, int) {
      grids_[g].grid->ComputeWeights(begin, end);
    });
  }
  for (int parity = 0; parity < 2; ++parity) {
    std::vector<std::pair<uint32_t, int>> jobs;  // (grid, slab)
    std::vector<size_t> weights;
    for (size_t g = 0; g < grids_.size(); ++g) {
      const NufftGrid& grid = *grids_[g].grid;
      for (int s = parity; s < grid.slabs(); s += 2) {
        jobs.push_back({static_cast<uint32_t>(g), s});
        weights.push_back(grid.SlabEnd(s) - grid.SlabBegin(s));
      }
    }
    RunBalanced(weights, [&](size_t j, int worker) {
      NufftGrid& grid = *grids_[jobs[j].first].grid;
      grid.SpreadRange(grid.SlabBegin(jobs[j].second), grid.SlabEnd(jobs[j].second),
                       &scratch_[static_cast<size_t>(worker)]);
    });
  }
  pool_.ParallelFor(grids_.size(), [&](size_t begin, size_t end, int) {
    for (size_t g = begin; g < end; ++g) grids_[g].grid->FinishSpread();
  });
  for (Piece& p : grids_) p.grid->SetStrengths(nullptr);
  spectrum->resize(nk);
  pool_.ParallelFor(nk, [&](size_t begin, size_t end, int) {
    for (size_t i = begin; i < end; ++i) {
      (*spectrum)[i] = grids_[grid_of_[i]].grid->Mode(local_of_[i]);
    }
  });
}

void FastEngine::EvaluateWeighted(const PointSet& points, const std::vector<double>& strengths,
                                  std::vector<std::complex<double>>* spectrum) {
  if (k_.empty() || points.empty()) {
    spectrum->assign(k_.size(), std::complex<double>(0.0));
    return;
  }
  // Kept weights would carry the strengths; no type-2 pass follows here.
  TypeOne(points, strengths.data(), /*keep_allowed=*/false, spectrum);
}

void FastEngine::Evaluate(const PointSet& points, bool with_gradient, SpectrumEvaluation* out) {
  const size_t n = points.size();
  const size_t nk = k_.size();
  out->spectrum.resize(nk);
  out->gradient.clear();
  out->loss = 0.0;
  if (nk == 0 || n == 0) {
    std::fill(out->spectrum.begin(), out->spectrum.end(), std::complex<double>(0.0));
    if (with_gradient) out->gradient.assign(n, {0.0, 0.0});
    return;
  }

  TypeOne(points, nullptr, /*keep_allowed=*/true, &out->spectrum);
  const bool weighted = !weights_.empty();
  double power = 0.0;
  for (size_t i = 0; i < nk; ++i) {
    const double p = std::norm(out->spectrum[i]);
    power += weighted ? weights_[i] * p : p;
  }
  const double dn = static_cast<double>(n);
  out->loss = power / (dn * static_cast<double>(nk));
  if (!with_gradient) return;

  // Type 2. Over K, sum_v v Im(conj(F_v) e_j(v)) = (1 / 2i) sum over +-K of
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
        const std::complex<double> f =
            weighted ? weights_[p.members[i]] * out->spectrum[p.members[i]]
                     : out->spectrum[p.members[i]];
        const std::complex<double> dir(v.a, v.b);
        p.grid->AddCoefficients(i, dir * std::conj(f), -dir * f);
      }
      p.grid->FinishCoefficients();
    }
  });
  sums_.resize(grids_.size());
  for (auto& s : sums_) s.resize(n);
  RunOverGrids(n, [&](size_t g, size_t begin, size_t end, int worker) {
    grids_[g].grid->InterpolateRange(begin, end, sums_[g].data(),
                                     &scratch_[static_cast<size_t>(worker)]);
  });
  const double scale = 4.0 * kPi / (dn * static_cast<double>(nk));
  out->gradient.resize(n);
  pool_.ParallelFor(n, [&](size_t begin, size_t end, int) {
    for (size_t j = begin; j < end; ++j) {
      std::complex<double> t = 0.0;
      for (const auto& s : sums_) t += s[j];
      out->gradient[j] = {0.5 * scale * t.imag(), -0.5 * scale * t.real()};
    }
  });
}

}  // namespace alignset

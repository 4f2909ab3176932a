#include "core/spectral/direct_engine.h"

#include <algorithm>
#include <cmath>

#include "core/util/angles.h"

namespace alignset {
namespace {

// Points per block: the tables of one block (split re/im, kBlock wide) stay in
// L2 for N = 65536 (about 3000 rows * 16 * 16 B = 0.8 MB), and the inner loop
// is kBlock wide so the compiler vectorizes it.
constexpr int kBlock = 16;
// A table row is taken from sincos every kExactStride entries and by complex
// products in between: the error stays within ~kExactStride ulps while the
// number of sincos calls drops by that factor.
constexpr int kExactStride = 16;
// Partial spectra summed independently; fixed so results do not depend on
// the thread count.
constexpr size_t kChunks = 32;

// Fills re/im[(t)*kBlock + jj] = exp(-2 pi i (lo + t) u_jj) for t in [0, count).
void FillTable(const double* u, int valid, int lo, int count, double* re, double* im) {
  for (int jj = 0; jj < kBlock; ++jj) {
    if (jj >= valid) {
      for (int t = 0; t < count; ++t) re[t * kBlock + jj] = im[t * kBlock + jj] = 0.0;
      continue;
    }
    const double x = u[jj];
    const double step_re = std::cos(2.0 * kPi * x), step_im = -std::sin(2.0 * kPi * x);
    double cr = 0.0, ci = 0.0;
    for (int t = 0; t < count; ++t) {
      if (t % kExactStride == 0) {
        const double ph = static_cast<double>(lo + t) * x;
        const double frac = ph - std::round(ph);
        cr = std::cos(2.0 * kPi * frac);
        ci = -std::sin(2.0 * kPi * frac);
      } else {
        const double nr = cr * step_re - ci * step_im;
        ci = cr * step_im + ci * step_re;
        cr = nr;
      }
      re[t * kBlock + jj] = cr;
      im[t * kBlock + jj] = ci;
    }
  }
}

}  // namespace

DirectEngine::DirectEngine(int threads) : pool_(threads) {}

void DirectEngine::SetFrequencies(const std::vector<Frequency>& k) {
  k_ = k;
  weights_.clear();
  a_min_ = 0;
  a_max_ = 0;
  b_max_ = 0;
  for (const Frequency& v : k_) {
    a_min_ = std::min(a_min_, v.a);
    a_max_ = std::max(a_max_, v.a);
    b_max_ = std::max(b_max_, v.b);
  }
}

void DirectEngine::SetLossWeights(std::vector<double> weights) { weights_ = std::move(weights); }

void DirectEngine::FillBlock(const PointSet& points, const double* strengths, size_t block,
                             BlockTables* t) const {
  const size_t n = points.size();
  const int a_count = a_max_ - a_min_ + 1;
  const int b_count = b_max_ + 1;
  double xs[kBlock], ys[kBlock];
  const size_t first = block * kBlock;
  const int valid = static_cast<int>(std::min<size_t>(kBlock, n - first));
  for (int jj = 0; jj < valid; ++jj) {
    xs[jj] = points[first + jj].x;
    ys[jj] = points[first + jj].y;
  }
  t->xr.resize(static_cast<size_t>(a_count) * kBlock);
  t->xi.resize(t->xr.size());
  t->yr.resize(static_cast<size_t>(b_count) * kBlock);
  t->yi.resize(t->yr.size());
  FillTable(xs, valid, a_min_, a_count, t->xr.data(), t->xi.data());
  FillTable(ys, valid, 0, b_count, t->yr.data(), t->yi.data());
  if (strengths == nullptr) return;
  for (int row = 0; row < a_count; ++row) {
    for (int jj = 0; jj < valid; ++jj) {
      t->xr[static_cast<size_t>(row) * kBlock + jj] *= strengths[first + jj];
      t->xi[static_cast<size_t>(row) * kBlock + jj] *= strengths[first + jj];
    }
  }
}

void DirectEngine::Spectrum(const PointSet& points, const double* strengths,
                            std::vector<std::complex<double>>* spectrum) {
  const size_t n = points.size();
  const size_t nk = k_.size();
  const size_t blocks = (n + kBlock - 1) / kBlock;
  spectrum->assign(nk, {0.0, 0.0});
  if (n == 0 || nk == 0) return;

  // The blocks are cut into a fixed number of chunks, each summed into its
  // own partial spectrum, and the partials are added in order. The chunking
  // does not depend on the thread count, so the result is bit-identical
  // whatever the number of threads.
  const size_t chunks = std::min<size_t>(blocks, kChunks);
  std::vector<std::vector<double>> partial(chunks, std::vector<double>(2 * nk, 0.0));
  pool_.ParallelFor(chunks, [&](size_t chunk_begin, size_t chunk_end, int) {
   BlockTables t;
   for (size_t chunk = chunk_begin; chunk < chunk_end; ++chunk) {
    double* acc = partial[chunk].data();
    size_t begin, end;
    ChunkBounds(blocks, static_cast<int>(chunk), static_cast<int>(chunks), &begin, &end);
    for (size_t block = begin; block < end; ++block) {
      FillBlock(points, strengths, block, &t);
      for (size_t q = 0; q < nk; ++q) {
        const double* xr = &t.xr[static_cast<size_t>(k_[q].a - a_min_) * kBlock];
        const double* xi = &t.xi[static_cast<size_t>(k_[q].a - a_min_) * kBlock];
        const double* yr = &t.yr[static_cast<size_t>(k_[q].b) * kBlock];
        const double* yi = &t.yi[static_cast<size_t>(k_[q].b) * kBlock];
        double sr = 0.0, si = 0.0;
        for (int jj = 0; jj < kBlock; ++jj) {
          sr += xr[jj] * yr[jj] - xi[jj] * yi[jj];
          si += xr[jj] * yi[jj] + xi[jj] * yr[jj];
        }
        acc[2 * q] += sr;
        acc[2 * q + 1] += si;
      }
    }
   }
  });
  for (size_t q = 0; q < nk; ++q) {
    double re = 0.0, im = 0.0;
    for (size_t c = 0; c < chunks; ++c) {
      re += partial[c][2 * q];
      im += partial[c][2 * q + 1];
    }
    (*spectrum)[q] = {re, im};
  }
}

void DirectEngine::EvaluateWeighted(const PointSet& points, const std::vector<double>& strengths,
                                    std::vector<std::complex<double>>* spectrum) {
  Spectrum(points, strengths.data(), spectrum);
}

void DirectEngine::Evaluate(const PointSet& points, bool with_gradient, SpectrumEvaluation* out) {
  const size_t n = points.size();
  const size_t nk = k_.size();
  const size_t blocks = (n + kBlock - 1) / kBlock;
  const bool weighted = !weights_.empty();

  Spectrum(points, nullptr, &out->spectrum);
  double power = 0.0;
  for (size_t q = 0; q < nk; ++q) {
    const double p = std::norm(out->spectrum[q]);
    power += weighted ? weights_[q] * p : p;
  }
  const double dn = static_cast<double>(std::max<size_t>(n, 1));
  out->loss = nk == 0 ? 0.0 : power / (dn * static_cast<double>(nk));

  out->gradient.clear();
  if (!with_gradient) return;
  out->gradient.assign(n, {0.0, 0.0});
  if (nk == 0) return;

  // Pass 2 (type 2): grad_j = scale * sum_v v Im(conj(F_v) e_j(v)). The block
  // tables are rebuilt rather than kept from pass 1: keeping them for every
  // block would take N * (a_count + b_count) * 16 bytes (2 GB at N = 65536),
  // and building them costs far less than the N * |K| products.
  const double scale = 4.0 * kPi / (dn * static_cast<double>(nk));
  pool_.ParallelFor(blocks, [&](size_t begin, size_t end, int) {
    BlockTables t;
    for (size_t block = begin; block < end; ++block) {
      FillBlock(points, nullptr, block, &t);
      double gx[kBlock] = {}, gy[kBlock] = {};
      for (size_t q = 0; q < nk; ++q) {
        const double wq = weighted ? weights_[q] : 1.0;
        const double cr = wq * out->spectrum[q].real(), ci = -wq * out->spectrum[q].imag();
        const double fa = k_[q].a, fb = k_[q].b;
        const double* xr = &t.xr[static_cast<size_t>(k_[q].a - a_min_) * kBlock];
        const double* xi = &t.xi[static_cast<size_t>(k_[q].a - a_min_) * kBlock];
        const double* yr = &t.yr[static_cast<size_t>(k_[q].b) * kBlock];
        const double* yi = &t.yi[static_cast<size_t>(k_[q].b) * kBlock];
        for (int jj = 0; jj < kBlock; ++jj) {
          const double er = xr[jj] * yr[jj] - xi[jj] * yi[jj];
          const double ei = xr[jj] * yi[jj] + xi[jj] * yr[jj];
          const double im = cr * ei + ci * er;
          gx[jj] += fa * im;
          gy[jj] += fb * im;
        }
      }
      const size_t first = block * kBlock;
      const int valid = static_cast<int>(std::min<size_t>(kBlock, n - first));
      for (int jj = 0; jj < valid; ++jj) {
        out->gradient[first + jj] = {scale * gx[jj], scale * gy[jj]};
      }
    }
  });
}

}  // namespace alignset

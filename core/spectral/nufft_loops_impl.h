// The NUFFT inner loops, included once per instruction set by
// core/nufft_loops_<isa>.cc with ALIGNSET_NUFFT_ISA naming the variant.
// Everything here has internal linkage (anonymous namespace) and calls no
// inline function of another header (the AVX2 intrinsics are always inlined
// and never emitted on their own), so no code compiled for one ISA can be
// merged into the other by the linker.
#ifndef ALIGNSET_NUFFT_ISA
#error "define ALIGNSET_NUFFT_ISA before including core/nufft_loops_impl.h"
#endif

#include <complex>
#include <cstddef>

#if defined(__AVX2__) && defined(__FMA__)
#include <immintrin.h>
#endif

#include "core/spectral/nufft_kernel.h"
#include "core/spectral/nufft_loops.h"

namespace alignset {
namespace {

// First grid index f = ceil(x - W/2), wrapped into [0, n), and the Horner
// variable y in [-1, 1] of the tap polynomials.
template <int W>
inline int FirstIndex(double x, double* y) {
  const double shifted = x - 0.5 * W;
  int f = static_cast<int>(shifted);  // truncation toward zero ...
  if (static_cast<double>(f) < shifted) ++f;  // ... corrected upwards
  *y = 2.0 * (x - f) - (W - 1);
  return f;
}

inline int Wrap(int f, int n) {
  if (f < 0) f += n;
  if (f >= n) f -= n;
  return f;
}

// D: the polynomial degree, a compile-time constant in the common case.
// Points go in groups of kLanes: each tap's Horner recurrence then runs on
// a vector of points (one multiply-add per lane per degree, coefficients
// broadcast), which vectorizes whatever the width.
constexpr int kLanes = 4;

template <int W, int D>
void WeightsW(const double* coefficients, int runtime_degree, const double* x, size_t count,
              int n, double* k, int* first) {
  const int degree = D >= 0 ? D : runtime_degree;
  size_t i = 0;
  for (; i + kLanes <= count; i += kLanes) {
    double y[kLanes];
    for (int l = 0; l < kLanes; ++l) first[i + l] = Wrap(FirstIndex<W>(x[i + l], &y[l]), n);
    for (int t = 0; t < W; ++t) {
      const double* c = coefficients + static_cast<size_t>(degree) * W + t;
      double v[kLanes];
      for (int l = 0; l < kLanes; ++l) v[l] = *c;
      for (int d = degree - 1; d >= 0; --d) {
        c -= W;
        const double cd = *c;
        for (int l = 0; l < kLanes; ++l) v[l] = v[l] * y[l] + cd;
      }
      for (int l = 0; l < kLanes; ++l) k[(i + l) * W + t] = v[l];
    }
  }
  for (; i < count; ++i) {
    double y;
    first[i] = Wrap(FirstIndex<W>(x[i], &y), n);
    for (int t = 0; t < W; ++t) {
      const double* c = coefficients + static_cast<size_t>(degree) * W + t;
      double v = *c;
      for (int d = degree - 1; d >= 0; --d) {
        c -= W;
        v = v * y + *c;
      }
      k[i * W + t] = v;
    }
  }
}

template <int W>
void SpreadW(double* grid, size_t stride, const double* k1, const double* k2, const int* row,
             const int* col, size_t count) {
  for (size_t i = 0; i < count; ++i) {
    const double* a = k1 + i * W;
    const double* b = k2 + i * W;
    double bv[W];
    for (int t = 0; t < W; ++t) bv[t] = b[t];
    double* g = grid + static_cast<size_t>(row[i]) * stride + col[i];
    for (int t1 = 0; t1 < W; ++t1, g += stride) {
      const double s = a[t1];
      for (int t2 = 0; t2 < W; ++t2) g[t2] += s * bv[t2];
    }
  }
}

template <int W>
void InterpolatePortableW(const std::complex<double>* grid, size_t stride, const double* k1,
                          const double* k2, const int* row, const int* col, size_t count,
                          std::complex<double>* out) {
  const double* g0 = reinterpret_cast<const double*>(grid);
  double* o = reinterpret_cast<double*>(out);
  for (size_t i = 0; i < count; ++i) {
    const double* a = k1 + i * W;
    const double* b = k2 + i * W;
    // sum_t1 sum_t2 a_t1 b_t2 g[t1][t2] = sum_t2 b_t2 (sum_t1 a_t1 g[t1][t2]):
    // the inner sums run over contiguous interleaved (re, im) pairs with one
    // multiply-add each; the column weights come last.
    double acc[2 * W];
    for (int t = 0; t < 2 * W; ++t) acc[t] = 0.0;
    const double* g = g0 + 2 * (static_cast<size_t>(row[i]) * stride + col[i]);
    for (int t1 = 0; t1 < W; ++t1, g += 2 * stride) {
      const double s = a[t1];
      for (int t = 0; t < 2 * W; ++t) acc[t] += s * g[t];
    }
    double re = 0.0, im = 0.0;
    for (int t = 0; t < W; ++t) {
      re += b[t] * acc[2 * t];
      im += b[t] * acc[2 * t + 1];
    }
    o[2 * i] = re;
    o[2 * i + 1] = im;
  }
}

#if defined(__AVX2__) && defined(__FMA__)
// The portable loop's sums with the 2W accumulators held in registers.
// Written with intrinsics because the compiler, given the array form, zeroes
// the accumulators with a string store and keeps part of them on the stack
// (1.3-2.7x slower by width, 1.45x at width 12).
//
// It gives the bits the compiled portable loop gave in this file before,
// so that no served set changes: the same additions in the same order (each
// accumulator over the rows in turn, then the column weights in column
// order as fused multiply-adds), and the rows' multiply-adds fused or not as
// the compiler had contracted them (kFusedRows: not at widths 6 and 8). At
// widths 5 and 7 its choices were mixed within a point, so those keep the
// portable loop (InterpolateW below).
template <int W, bool kFusedRows>
void InterpolateAvx2W(const std::complex<double>* grid, size_t stride, const double* k1,
                      const double* k2, const int* row, const int* col, size_t count,
                      std::complex<double>* out) {
  constexpr int kFull = (2 * W) / 4;        // (re, im) pairs 0 .. 2 kFull - 1, two a register
  constexpr bool kTail = (2 * W) % 4 != 0;  // the last pair of an odd width
  const double* g0 = reinterpret_cast<const double*>(grid);
  double* o = reinterpret_cast<double*>(out);
  for (size_t i = 0; i < count; ++i) {
    const double* a = k1 + i * W;
    const double* b = k2 + i * W;
    __m256d acc[kFull > 0 ? kFull : 1];
    __m128d tail = _mm_setzero_pd();
#pragma GCC unroll 16
    for (int v = 0; v < kFull; ++v) acc[v] = _mm256_setzero_pd();
    const double* g = g0 + 2 * (static_cast<size_t>(row[i]) * stride + col[i]);
#pragma GCC unroll 16
    for (int t1 = 0; t1 < W; ++t1, g += 2 * stride) {
      const __m256d s = _mm256_broadcast_sd(a + t1);
#pragma GCC unroll 16
      for (int v = 0; v < kFull; ++v) {
        const __m256d row_values = _mm256_loadu_pd(g + 4 * v);
        if constexpr (kFusedRows) {
          acc[v] = _mm256_fmadd_pd(s, row_values, acc[v]);
        } else {
          __m256d product = _mm256_mul_pd(s, row_values);
          asm("" : "+x"(product));  // keeps the compiler from fusing it into the add
          acc[v] = _mm256_add_pd(acc[v], product);
        }
      }
      if constexpr (kTail) {
        const __m128d s2 = _mm256_castpd256_pd128(s);
        const __m128d row_values = _mm_loadu_pd(g + 4 * kFull);
        if constexpr (kFusedRows) {
          tail = _mm_fmadd_pd(s2, row_values, tail);
        } else {
          __m128d product = _mm_mul_pd(s2, row_values);
          asm("" : "+x"(product));
          tail = _mm_add_pd(tail, product);
        }
      }
    }
    __m128d sum = _mm_setzero_pd();
#pragma GCC unroll 16
    for (int t = 0; t < W; ++t) {
      __m128d pair;
      if (t / 2 < kFull) {
        pair = t % 2 == 0 ? _mm256_castpd256_pd128(acc[t / 2]) : _mm256_extractf128_pd(acc[t / 2], 1);
      } else {
        pair = tail;
      }
      sum = _mm_fmadd_pd(_mm_set1_pd(b[t]), pair, sum);
    }
    _mm_storeu_pd(o + 2 * i, sum);
  }
}
#endif

template <int W>
void InterpolateW(const std::complex<double>* grid, size_t stride, const double* k1,
                  const double* k2, const int* row, const int* col, size_t count,
                  std::complex<double>* out) {
#if defined(__AVX2__) && defined(__FMA__)
  if constexpr (W != 5 && W != 7) {
    InterpolateAvx2W<W, W != 6 && W != 8>(grid, stride, k1, k2, row, col, count, out);
    return;
  }
#endif
  InterpolatePortableW<W>(grid, stride, k1, k2, row, col, count, out);
}

void Weights(const double* coefficients, int degree, int width, const double* x, size_t count,
             int n, double* k, int* first) {
  switch (width) {
#define ALIGNSET_CASE(W) \
  case W:                                                                          \
    if (degree == TapPolynomialDegree(W)) {                                        \
      return WeightsW<W, TapPolynomialDegree(W)>(coefficients, degree, x, count, n, k, first); \
    }                                                                              \
    return WeightsW<W, -1>(coefficients, degree, x, count, n, k, first);
    ALIGNSET_CASE(2) ALIGNSET_CASE(3) ALIGNSET_CASE(4) ALIGNSET_CASE(5) ALIGNSET_CASE(6)
    ALIGNSET_CASE(7) ALIGNSET_CASE(8) ALIGNSET_CASE(9) ALIGNSET_CASE(10) ALIGNSET_CASE(11)
    ALIGNSET_CASE(12) ALIGNSET_CASE(13) ALIGNSET_CASE(14) ALIGNSET_CASE(15) ALIGNSET_CASE(16)
#undef ALIGNSET_CASE
    default: return;
  }
}

void Spread(double* grid, size_t stride, int width, const double* k1, const double* k2,
            const int* row, const int* col, size_t count) {
  switch (width) {
#define ALIGNSET_CASE(W) \
  case W: return SpreadW<W>(grid, stride, k1, k2, row, col, count);
    ALIGNSET_CASE(2) ALIGNSET_CASE(3) ALIGNSET_CASE(4) ALIGNSET_CASE(5) ALIGNSET_CASE(6)
    ALIGNSET_CASE(7) ALIGNSET_CASE(8) ALIGNSET_CASE(9) ALIGNSET_CASE(10) ALIGNSET_CASE(11)
    ALIGNSET_CASE(12) ALIGNSET_CASE(13) ALIGNSET_CASE(14) ALIGNSET_CASE(15) ALIGNSET_CASE(16)
#undef ALIGNSET_CASE
    default: return;
  }
}

void Interpolate(const std::complex<double>* grid, size_t stride, int width, const double* k1,
                 const double* k2, const int* row, const int* col, size_t count,
                 std::complex<double>* out) {
  switch (width) {
#define ALIGNSET_CASE(W) \
  case W: return InterpolateW<W>(grid, stride, k1, k2, row, col, count, out);
    ALIGNSET_CASE(2) ALIGNSET_CASE(3) ALIGNSET_CASE(4) ALIGNSET_CASE(5) ALIGNSET_CASE(6)
    ALIGNSET_CASE(7) ALIGNSET_CASE(8) ALIGNSET_CASE(9) ALIGNSET_CASE(10) ALIGNSET_CASE(11)
    ALIGNSET_CASE(12) ALIGNSET_CASE(13) ALIGNSET_CASE(14) ALIGNSET_CASE(15) ALIGNSET_CASE(16)
#undef ALIGNSET_CASE
    default: return;
  }
}

}  // namespace

const NufftLoops& ALIGNSET_NUFFT_ISA() {
  static const NufftLoops loops = {Weights, Spread, Interpolate, ALIGNSET_NUFFT_ISA_NAME};
  return loops;
}

}  // namespace alignset

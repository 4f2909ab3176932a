#include "core/spectral/cuda/cuda_engine.h"

#include <cuda_runtime.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

namespace alignset {
namespace {

constexpr int kThreads = 256;
constexpr double kPiDouble = 3.14159265358979323846;
// Partial spectra per frequency: the points are cut into this many chunks
// (fixed, so the order of summation never changes) to give the GPU enough
// blocks when |K| is small.
constexpr int kPointChunks = 16;

// exp(-2 pi i phase / 2^64): the phase is a fixed-point fraction of a turn;
// read as a signed 64-bit number it lies in [-1/2, 1/2) turns, and
// sincospi wants the angle in units of pi, i.e. 2 * turns.
__device__ inline void Phasor(uint64_t phase, double* c, double* s) {
  const double half_turns = static_cast<double>(static_cast<int64_t>(phase)) * 0x1p-63;
  sincospi(half_turns, s, c);
}

// partial[chunk * nk + q] = sum over the chunk's points of
// f_j exp(-2 pi i v_q.s_j), with f_j = strengths[j], or 1 when strengths is
// null.
__global__ void SpectrumKernel(const int2* __restrict__ k, int nk,
                               const ulonglong2* __restrict__ pts,
                               const double* __restrict__ strengths, int n,
                               double2* __restrict__ partial) {
  __shared__ ulonglong2 tile[kThreads];
  __shared__ double tile_f[kThreads];
  const int q = blockIdx.x * blockDim.x + threadIdx.x;
  const int chunk = blockIdx.y;
  const int begin = static_cast<int>(static_cast<int64_t>(n) * chunk / gridDim.y);
  const int end = static_cast<int>(static_cast<int64_t>(n) * (chunk + 1) / gridDim.y);
  uint64_t a = 0, b = 0;
  if (q < nk) {
    a = static_cast<uint64_t>(static_cast<int64_t>(k[q].x));
    b = static_cast<uint64_t>(static_cast<int64_t>(k[q].y));
  }
  double re = 0.0, im = 0.0;
  for (int base = begin; base < end; base += kThreads) {
    const int j = base + threadIdx.x;
    if (j < end) {
      tile[threadIdx.x] = pts[j];
      tile_f[threadIdx.x] = strengths != nullptr ? strengths[j] : 1.0;
    }
    __syncthreads();
    const int count = min(kThreads, end - base);
    if (q < nk) {
      for (int t = 0; t < count; ++t) {
        double c, s;
        Phasor(a * tile[t].x + b * tile[t].y, &c, &s);
        re += tile_f[t] * c;
        im -= tile_f[t] * s;
      }
    }
    __syncthreads();
  }
  if (q < nk) partial[static_cast<size_t>(chunk) * nk + q] = make_double2(re, im);
}

__global__ void ReduceKernel(const double2* __restrict__ partial, int nk, int chunks,
                             double2* __restrict__ spectrum) {
  const int q = blockIdx.x * blockDim.x + threadIdx.x;
  if (q >= nk) return;
  double re = 0.0, im = 0.0;
  for (int c = 0; c < chunks; ++c) {
    re += partial[static_cast<size_t>(c) * nk + q].x;
    im += partial[static_cast<size_t>(c) * nk + q].y;
  }
  spectrum[q] = make_double2(re, im);
}

// grad_j = scale * sum_v v Im(conj(F_v) exp(-2 pi i v.s_j)).
__global__ void GradientKernel(const int2* __restrict__ k, const double2* __restrict__ spectrum,
                               int nk, const ulonglong2* __restrict__ pts, int n, double scale,
                               double2* __restrict__ grad) {
  __shared__ int2 kt[kThreads];
  __shared__ double2 ft[kThreads];
  const int j = blockIdx.x * blockDim.x + threadIdx.x;
  ulonglong2 p = make_ulonglong2(0, 0);
  if (j < n) p = pts[j];
  double gx = 0.0, gy = 0.0;
  for (int base = 0; base < nk; base += kThreads) {
    const int q = base + threadIdx.x;
    if (q < nk) {
      kt[threadIdx.x] = k[q];
      ft[threadIdx.x] = spectrum[q];
    }
    __syncthreads();
    const int count = min(kThreads, nk - base);
    if (j < n) {
      for (int t = 0; t < count; ++t) {
        const uint64_t a = static_cast<uint64_t>(static_cast<int64_t>(kt[t].x));
        const uint64_t b = static_cast<uint64_t>(static_cast<int64_t>(kt[t].y));
        double c, s;
        Phasor(a * p.x + b * p.y, &c, &s);
        // conj(F) (c - i s) has imaginary part -(Fr s + Fi c).
        const double im = -(ft[t].x * s + ft[t].y * c);
        gx += kt[t].x * im;
        gy += kt[t].y * im;
      }
    }
    __syncthreads();
  }
  if (j < n) grad[j] = make_double2(scale * gx, scale * gy);
}

// x mod 1 as a 64-bit fixed-point fraction of a turn (truncation error
// below 2^-64, far under a double's own resolution of the phase).
uint64_t ToFixed(double x) {
  double w = x - std::floor(x);
  if (!(w >= 0.0 && w < 1.0)) w = 0.0;  // NaN or the rounding of -tiny to 1
  return static_cast<uint64_t>(std::ldexp(w, 64));
}

template <typename T>
class DeviceBuffer {
 public:
  ~DeviceBuffer() { cudaFree(ptr_); }
  cudaError_t Reserve(size_t count) {
    if (count <= capacity_) return cudaSuccess;
    cudaFree(ptr_);
    ptr_ = nullptr;
    capacity_ = 0;
    const cudaError_t e = cudaMalloc(&ptr_, std::max<size_t>(count, 1) * sizeof(T));
    if (e == cudaSuccess) capacity_ = count;
    return e;
  }
  T* get() const { return ptr_; }

 private:
  T* ptr_ = nullptr;
  size_t capacity_ = 0;
};

class CudaEngine final : public SpectralEngine {
 public:
  explicit CudaEngine(int device) : device_(device) {}
  std::string name() const override { return "cuda"; }

  void SetFrequencies(const std::vector<Frequency>& k) override {
    k_ = k;
    k_uploaded_ = false;
    weights_.clear();
  }

  void SetLossWeights(std::vector<double> weights) override { weights_ = std::move(weights); }

  void EvaluateWeighted(const PointSet& points, const std::vector<double>& strengths,
                        std::vector<std::complex<double>>* spectrum) override {
    const size_t nk = k_.size();
    spectrum->assign(nk, {0.0, 0.0});
    if (points.empty() || nk == 0) return;
    std::vector<double2> f;
    if (Spectrum(points, strengths.data(), &f) != cudaSuccess) {
      const double nan = std::numeric_limits<double>::quiet_NaN();
      spectrum->assign(nk, {nan, nan});
      return;
    }
    for (size_t q = 0; q < nk; ++q) (*spectrum)[q] = {f[q].x, f[q].y};
  }

  // The interface has no error channel: a CUDA failure yields NaN, which
  // the optimizer treats as divergence (and callers can detect).
  void Evaluate(const PointSet& points, bool with_gradient, SpectrumEvaluation* out) override {
    const size_t n = points.size(), nk = k_.size();
    out->spectrum.assign(nk, {0.0, 0.0});
    out->gradient.clear();
    if (with_gradient) out->gradient.assign(n, {0.0, 0.0});
    out->loss = 0.0;
    if (n == 0 || nk == 0) return;
    if (Run(points, with_gradient, out) != cudaSuccess) {
      const double nan = std::numeric_limits<double>::quiet_NaN();
      out->spectrum.assign(nk, {nan, nan});
      if (with_gradient) out->gradient.assign(n, {nan, nan});
      out->loss = nan;
    }
  }

 private:
  // F over K into `spectrum` (host), leaving it on the device too; null
  // strengths mean 1.
  cudaError_t Spectrum(const PointSet& points, const double* strengths,
                       std::vector<double2>* spectrum) {
    const int n = static_cast<int>(points.size()), nk = static_cast<int>(k_.size());
    cudaError_t e = cudaSetDevice(device_);
    if (e != cudaSuccess) return e;
    if (!k_uploaded_) {
      std::vector<int2> host(nk);
      for (int q = 0; q < nk; ++q) host[q] = make_int2(k_[q].a, k_[q].b);
      if ((e = k_dev_.Reserve(nk)) != cudaSuccess) return e;
      if ((e = cudaMemcpy(k_dev_.get(), host.data(), nk * sizeof(int2), cudaMemcpyHostToDevice)) !=
          cudaSuccess) {
        return e;
      }
      k_uploaded_ = true;
    }
    std::vector<ulonglong2> fixed(n);
    for (int j = 0; j < n; ++j) {
      fixed[j] = make_ulonglong2(ToFixed(points[j].x), ToFixed(points[j].y));
    }
    const int chunks = std::max(1, std::min(kPointChunks, n / kThreads));
    if ((e = pts_dev_.Reserve(n)) != cudaSuccess) return e;
    if ((e = partial_dev_.Reserve(static_cast<size_t>(chunks) * nk)) != cudaSuccess) return e;
    if ((e = spectrum_dev_.Reserve(nk)) != cudaSuccess) return e;
    if ((e = cudaMemcpy(pts_dev_.get(), fixed.data(), n * sizeof(ulonglong2),
                        cudaMemcpyHostToDevice)) != cudaSuccess) {
      return e;
    }
    const double* strengths_dev = nullptr;
    if (strengths != nullptr) {
      if ((e = strengths_dev_.Reserve(n)) != cudaSuccess) return e;
      if ((e = cudaMemcpy(strengths_dev_.get(), strengths, n * sizeof(double),
                          cudaMemcpyHostToDevice)) != cudaSuccess) {
        return e;
      }
      strengths_dev = strengths_dev_.get();
    }
    const dim3 grid1((nk + kThreads - 1) / kThreads, chunks);
    SpectrumKernel<<<grid1, kThreads>>>(k_dev_.get(), nk, pts_dev_.get(), strengths_dev, n,
                                        partial_dev_.get());
    ReduceKernel<<<(nk + kThreads - 1) / kThreads, kThreads>>>(partial_dev_.get(), nk, chunks,
                                                              spectrum_dev_.get());
    if ((e = cudaGetLastError()) != cudaSuccess) return e;
    spectrum->resize(nk);
    return cudaMemcpy(spectrum->data(), spectrum_dev_.get(), nk * sizeof(double2),
                      cudaMemcpyDeviceToHost);
  }

  cudaError_t Run(const PointSet& points, bool with_gradient, SpectrumEvaluation* out) {
    const int n = static_cast<int>(points.size()), nk = static_cast<int>(k_.size());
    std::vector<double2> spectrum;
    cudaError_t e = Spectrum(points, nullptr, &spectrum);
    if (e != cudaSuccess) return e;
    const bool weighted = !weights_.empty();
    double power = 0.0;
    for (int q = 0; q < nk; ++q) {
      out->spectrum[q] = {spectrum[q].x, spectrum[q].y};
      const double p = spectrum[q].x * spectrum[q].x + spectrum[q].y * spectrum[q].y;
      power += weighted ? weights_[q] * p : p;
    }
    out->loss = power / (static_cast<double>(n) * nk);
    if (!with_gradient) return cudaSuccess;
    if (weighted) {
      // The gradient sums w_v conj(F(v)) terms: hand it w F.
      for (int q = 0; q < nk; ++q) {
        spectrum[q] = make_double2(weights_[q] * spectrum[q].x, weights_[q] * spectrum[q].y);
      }
      if ((e = cudaMemcpy(spectrum_dev_.get(), spectrum.data(), nk * sizeof(double2),
                          cudaMemcpyHostToDevice)) != cudaSuccess) {
        return e;
      }
    }

    const double scale = 4.0 * kPiDouble / (static_cast<double>(n) * nk);
    if ((e = grad_dev_.Reserve(n)) != cudaSuccess) return e;
    GradientKernel<<<(n + kThreads - 1) / kThreads, kThreads>>>(
        k_dev_.get(), spectrum_dev_.get(), nk, pts_dev_.get(), n, scale, grad_dev_.get());
    if ((e = cudaGetLastError()) != cudaSuccess) return e;
    std::vector<double2> grad(n);
    if ((e = cudaMemcpy(grad.data(), grad_dev_.get(), n * sizeof(double2),
                        cudaMemcpyDeviceToHost)) != cudaSuccess) {
      return e;
    }
    for (int j = 0; j < n; ++j) out->gradient[j] = {grad[j].x, grad[j].y};
    return cudaSuccess;
  }

  int device_;
  std::vector<Frequency> k_;
  std::vector<double> weights_;  // loss weights; empty: all 1
  bool k_uploaded_ = false;
  DeviceBuffer<int2> k_dev_;
  DeviceBuffer<ulonglong2> pts_dev_;
  DeviceBuffer<double> strengths_dev_;
  DeviceBuffer<double2> partial_dev_;
  DeviceBuffer<double2> spectrum_dev_;
  DeviceBuffer<double2> grad_dev_;
};

}  // namespace

bool CudaDeviceAvailable(std::string* why) {
  int count = 0;
  const cudaError_t e = cudaGetDeviceCount(&count);
  if (e != cudaSuccess) {
    if (why) *why = std::string("no usable CUDA device (") + cudaGetErrorString(e) + ")";
    cudaGetLastError();  // clear the sticky error state of the runtime
    return false;
  }
  if (count == 0) {
    if (why) *why = "no CUDA device present";
    return false;
  }
  return true;
}

StatusOr<std::unique_ptr<SpectralEngine>> MakeCudaEngine(int threads) {
  (void)threads;  // the host side is light: conversions and copies only
  std::string why;
  if (!CudaDeviceAvailable(&why)) {
    return Status::Unavailable("the CUDA engine is built but cannot run: " + why);
  }
  return std::unique_ptr<SpectralEngine>(std::make_unique<CudaEngine>(0));
}

}  // namespace alignset

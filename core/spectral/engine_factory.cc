#include <memory>

#include "core/spectral/direct_engine.h"
#include "core/spectral/fast_engine.h"
#include "core/spectral/spectral_engine.h"
#ifdef ALIGNSET_HAVE_CUDA
#include "core/spectral/cuda/cuda_engine.h"
#endif

namespace alignset {

StatusOr<EngineKind> ParseEngineKind(const std::string& name) {
  if (name == "auto") return EngineKind::kAuto;
  if (name == "direct") return EngineKind::kDirect;
  if (name == "fast") return EngineKind::kFast;
  if (name == "cuda") return EngineKind::kCuda;
  return Status::InvalidArgument("unknown engine '" + name + "' (expected auto, direct, fast or cuda)");
}

std::string EngineKindName(EngineKind kind) {
  switch (kind) {
    case EngineKind::kAuto: return "auto";
    case EngineKind::kDirect: return "direct";
    case EngineKind::kFast: return "fast";
    case EngineKind::kCuda: return "cuda";
  }
  return "unknown";
}

namespace {

StatusOr<std::unique_ptr<SpectralEngine>> MakeCuda(int threads) {
#ifdef ALIGNSET_HAVE_CUDA
  return MakeCudaEngine(threads);
#else
  (void)threads;
  return Status::Unavailable(
      "the CUDA engine is not built in this binary (configure with nvcc available and "
      "-DALIGNSET_CUDA=AUTO or ON); use --engine fast or direct");
#endif
}

}  // namespace

StatusOr<std::unique_ptr<SpectralEngine>> MakeSpectralEngine(EngineKind kind, int threads) {
  switch (kind) {
    case EngineKind::kAuto: {
      // The GPU when one is built in and usable, else the fast CPU engine.
      auto cuda = MakeCuda(threads);
      if (cuda.ok()) return cuda;
      return std::unique_ptr<SpectralEngine>(std::make_unique<FastEngine>(threads));
    }
    case EngineKind::kDirect:
      return std::unique_ptr<SpectralEngine>(std::make_unique<DirectEngine>(threads));
    case EngineKind::kFast:
      return std::unique_ptr<SpectralEngine>(std::make_unique<FastEngine>(threads));
    case EngineKind::kCuda:
      return MakeCuda(threads);
  }
  return Status::InvalidArgument("unknown engine kind");
}

}  // namespace alignset

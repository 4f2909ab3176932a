#include <memory>

#include "core/direct_engine.h"
#include "core/spectral_engine.h"

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

StatusOr<std::unique_ptr<SpectralEngine>> MakeSpectralEngine(EngineKind kind, int threads) {
  switch (kind) {
    case EngineKind::kAuto:
    case EngineKind::kDirect:
      return std::unique_ptr<SpectralEngine>(std::make_unique<DirectEngine>(threads));
    case EngineKind::kFast:
      return Status::Unavailable("the fast NUFFT engine is not built yet");
    case EngineKind::kCuda:
      return Status::Unavailable("the CUDA engine is not built in this binary");
  }
  return Status::InvalidArgument("unknown engine kind");
}

}  // namespace alignset

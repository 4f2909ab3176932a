#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>

#include "render/pixel_samplers.h"
#include "render/spectral_estimator.h"
#include <alignset/client.h>
#include "core/util/status.h"

namespace alignset::render {

// One image with one sampler: what `alignset render` does, free of any
// command-line parser.
struct RenderRequest {
  std::string scene = "antialias";  // antialias | shadow
  std::string sampler;              // `alignset sample --list` names, or RenderSamplerNames()
  uint32_t spp = 0;
  bool reference = false;           // write the exact image instead (no sampler, no server)
  std::string out;                  // .npy, float64 (H, W), row y = pixel row y
  int size = 128;
  uint64_t seed = 1;
  LineOrientation orientation = LineOrientation::kNormal;  // line, segment
  double segment_length = 0.5;
  int threads = 2;
  // The direction estimator's pre-pass (spectral_estimator.h); "auto" picks
  // one by N and the scene's pixel domain (AutoPrepass).
  std::string prepass = kAutoPrepass;
  // Fold the pre-pass's samples into each pixel's estimate (prepass_reuse.h):
  // auto when the pre-pass allows it; on refuses one that does not;
  // unbiased as on, with the count weights on direction-less pixels too.
  PrepassReuse reuse_prepass = PrepassReuse::kAuto;
  // aligned-lattice*, aligned-tent-lattice*: the window of normals a
  // generator is chosen for (default 1 degree; tent kTentLatticeWindowDeg).
  std::optional<double> lattice_window_deg;
  // aligned-lattice* (local search): each key's lattice may have N' in
  // [N - span, N] points, the size whose generator scores best
  // (AlignedLatticeTable); 0 keeps N. The search costs span + 1 times as much.
  uint32_t lattice_size_span = 0;
  // aligned-lattice*, aligned-tent-lattice*: read the lattices a server has
  // chosen and cached (FetchAlignedSets with the construction) instead of
  // searching for them here; the server's window is the default one, so a
  // lattice_window_deg is refused with it. The image is the one the local
  // search gives.
  bool lattices_from_server = false;
  ConnectOptions server;  // aligned, aligned-exact, and the lattices from a server
};

// What came out: the MSE against the exact image over edge and smooth pixels.
struct RenderSummary {
  double mse_edge = 0.0, mse_smooth = 0.0, mse_all = 0.0;
  double seconds = 0.0;
  // The sample budget, every sample counted: the sampler's N plus the
  // integrand evaluations its direction pre-pass spent on each pixel (0 for
  // samplers that read no estimated direction).
  uint32_t samples_per_pixel = 0;
  uint32_t prepass_per_pixel = 0;
  bool prepass_reused = false;  // the pre-pass's samples are in the estimate
  uint32_t total_per_pixel() const { return samples_per_pixel + prepass_per_pixel; }
  std::string note;  // one line on what was used (estimator, sets fetched, tile)
};

// INVALID_ARGUMENT for a bad scene, sampler, N or output path; the server's
// Status (UNAVAILABLE, ...) when the aligned sets cannot be fetched.
StatusOr<RenderSummary> RunRender(
    const RenderRequest& request,
    const std::function<void(const std::string&, double, double, const std::string&)>& progress);

}  // namespace alignset::render

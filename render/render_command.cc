#include "render/render_command.h"

#include <chrono>
#include <cmath>
#include <cstdio>

#include <alignset/npy.h>

#include "render/direction.h"
#include "render/lattice_sets.h"
#include "core/optimize/aligned_lattice.h"
#include "render/renderer.h"
#include "render/scene.h"
#include "render/set_fetch.h"
#include "core/sampling/samplers.h"
#include "core/sampling/screen_space_rank1.h"

namespace alignset::render {

StatusOr<RenderSummary> RunRender(
    const RenderRequest& r,
    const std::function<void(const std::string&, double, double, const std::string&)>& progress) {
  const auto t0 = std::chrono::steady_clock::now();
  if (r.out.size() < 5 || r.out.compare(r.out.size() - 4, 4, ".npy") != 0) {
    return Status::InvalidArgument("--out must name a .npy file, got '" + r.out + "'");
  }
  auto scene = MakeScene(r.scene, r.size, r.size, r.seed);
  if (!scene.ok()) return scene.status();
  const std::vector<size_t> shape = {size_t(scene->height()), size_t(scene->width())};
  RenderSummary summary;
  if (r.reference) {
    if (Status s = WriteNpy(r.out, shape, scene->Reference()); !s.ok()) return s;
    summary.note = "exact reference";
    return summary;
  }
  const std::vector<std::string> extra = RenderSamplerNames();
  const std::vector<std::string> known = SamplerNames();
  if (std::find(extra.begin(), extra.end(), r.sampler) == extra.end() &&
      std::find(known.begin(), known.end(), r.sampler) == known.end()) {
    std::string all;
    for (const auto& n : known) all += n + ", ";
    for (const auto& n : extra) all += n + ", ";
    all.resize(all.size() - 2);
    return Status::InvalidArgument("unknown sampler '" + r.sampler + "' (known: " + all + ")");
  }
  if (r.spp < 1 || r.spp > 65536) {
    return Status::InvalidArgument("--spp must be in [1, 65536], got " + std::to_string(r.spp));
  }
  if (r.lattices_from_server) {
    if (r.sampler.rfind("aligned-lattice", 0) != 0 && r.sampler.rfind("aligned-tent-lattice", 0) != 0) {
      return Status::InvalidArgument("lattices from a server are for the aligned-lattice* and "
                                     "aligned-tent-lattice* samplers, not '" + r.sampler + "'");
    }
    if (r.lattice_window_deg) {
      return Status::InvalidArgument("a server chooses its lattices for its own window (1 degree; "
                                     "tent-folded 2): --lattice-window needs local lattices");
    }
  }
  if (r.lattice_size_span > 0) {
    if (r.sampler.rfind("aligned-lattice", 0) != 0 || r.lattices_from_server) {
      return Status::InvalidArgument("--lattice-size-span is for the aligned-lattice* samplers with local "
                                     "lattices, not '" + r.sampler + "'" +
                                     (r.lattices_from_server ? " from a server" : ""));
    }
    // Refused here, before the pre-pass, rather than when the table is built.
    if (Status s = CheckLatticeSizeSpan(r.spp, r.lattice_size_span); !s.ok()) return s;
  }
  const std::vector<PixelDirection> exact = GeometryDirections(*scene);
  auto prepass = ParsePrepass(r.prepass == kAutoPrepass ? AutoPrepass(r.spp, scene->domain()) : r.prepass);
  if (!prepass.ok()) return prepass.status();
  const std::unique_ptr<DirectionEstimator> estimator = MakeSpectralEstimator(*prepass);
  SamplerConfig c;
  c.name = r.sampler;
  c.n = r.spp;
  c.exact = &exact;
  c.orientation = r.orientation;
  c.segment_length = r.segment_length;
  // The pre-pass only for the samplers that read the estimated θ (it costs
  // about 3 ms per pixel with grid16).
  const bool uses_estimate = ReadsEstimatedDirections(c);
  const bool must_reuse =
      r.reuse_prepass == PrepassReuse::kOn || r.reuse_prepass == PrepassReuse::kUnbiased;
  if (uses_estimate && must_reuse && !prepass->Reusable()) {
    return Status::InvalidArgument(
        "pre-pass " + prepass->Name() + " cannot be reused in the estimate (a grid's mean is " +
        "biased or far noisier than the sampler's own); reuse needs samplesM or edgesM, or turn "
        "reuse off");
  }
  c.reuse_prepass = uses_estimate && r.reuse_prepass != PrepassReuse::kOff && prepass->Reusable();
  c.continue_prepass = r.reuse_prepass != PrepassReuse::kUnbiased;
  const std::vector<PixelDirection> estimated =
      uses_estimate ? EstimateDirections(*scene, *estimator, r.seed, r.threads)
                    : std::vector<PixelDirection>(scene->size());
  c.estimated = &estimated;
  RenderSets table;
  ShiftTile tile;
  const bool tent = r.sampler == "aligned-tent-lattice" || r.sampler == "aligned-tent-lattice-exact";
  const bool lattice_sampler = r.sampler == "aligned-lattice" || r.sampler == "aligned-lattice-exact" || tent;
  const bool optimized_sampler = r.sampler == "aligned" || r.sampler == "aligned-exact";
  // The pixels' estimated directions, or the geometry's (the -exact samplers).
  const bool estimated_dirs =
      r.sampler == "aligned" || r.sampler == "aligned-lattice" || r.sampler == "aligned-tent-lattice";
  if (optimized_sampler || (lattice_sampler && r.lattices_from_server)) {
    // From the server: the optimized sets, or the lattices it has chosen.
    const std::string construction = optimized_sampler ? "" : tent ? "tent-lattice" : "lattice";
    auto client = ServiceClient::Connect(r.server);
    if (!client.ok()) return client.status();
    const auto pairs = NeededPairs(estimated_dirs ? estimated : exact, c.policy);
    auto fetched = FetchAlignedSets(**client, r.spp, pairs, progress, construction);
    if (!fetched.ok()) return fetched.status();
    table = std::move(*fetched);
    c.sets = &table;
    summary.note = "46 one-direction keys and " + std::to_string(PairKeys(pairs).size()) + " pair keys (for " +
                   std::to_string(pairs.size()) + " served pairs) of " +
                   (optimized_sampler ? "sets" : tent ? "tent-folded lattices" : "lattices") + " from " +
                   r.server.address;
  } else if (lattice_sampler) {
    LatticeTableStats st;
    auto built = AlignedLatticeTable(
        r.spp, {estimated_dirs ? &estimated : &exact}, c.policy,
        r.lattice_window_deg.value_or(DefaultLatticeWindowDeg(tent)), r.threads, &st,
        [&](double done, double total) { progress("lattices", done, total, ""); }, tent, r.lattice_size_span);
    if (!built.ok()) return built.status();
    table = std::move(*built);
    c.sets = &table;
    char line[240];
    std::snprintf(line, sizeof line,
                  "%zu one-direction and %zu two-direction %slattices (%zu searches, one per canonical key%s) in %.2f s",
                  st.one, st.two, tent ? "tent-folded " : "", st.searched,
                  r.lattice_size_span > 0 ? " and size" : "", st.seconds);
    summary.note = line;
    if (r.lattice_size_span > 0) {
      std::snprintf(line, sizeof line, "; %zu keys below N, %.1f points a key on average", st.smaller,
                    st.mean_points);
      summary.note += line;
    }
  }
  if (r.sampler == "screen-space-rank1") {
    auto t = OptimizeShiftTile(r.spp, ShiftTileOptions{});
    if (!t.ok()) return t.status();
    tile = std::move(*t);
    c.tile = &tile;
    summary.note = "64x64 shift tile optimized for N = " + std::to_string(r.spp);
  }
  summary.samples_per_pixel = r.spp;
  if (uses_estimate) {
    summary.prepass_per_pixel = static_cast<uint32_t>(estimator->evaluations());
    summary.prepass_reused = c.reuse_prepass;
    summary.note += (summary.note.empty() ? "" : "; ") + std::string("directions: ") +
                    estimator->name() + " (" + std::to_string(estimator->evaluations()) +
                    " evaluations per pixel)";
  }
  auto sampler = MakePixelSampler(c);
  if (!sampler.ok()) return sampler.status();
  const std::vector<double> image = Render(*scene, **sampler, r.seed, r.threads);
  if (Status s = WriteNpy(r.out, shape, image); !s.ok()) return s;
  const ImageErrors e =
      MeasureErrors(image, scene->Reference(), scene->Classes(), scene->width(), scene->height(), {});
  summary.mse_edge = e.mse_edge;
  summary.mse_smooth = e.mse_smooth;
  summary.mse_all = e.mse_all;
  summary.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return summary;
}

}  // namespace alignset::render

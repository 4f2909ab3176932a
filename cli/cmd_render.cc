// `alignset render`: one image of one scene with one sampler, as a .npy
// array, so that anyone can compare a sampler with any tool. The command
// line around the renderer library render/ (alignset_render): built into the
// `alignset` binary when the client library is (cli/CMakeLists.txt).
#include <cstdio>
#include <map>
#include <memory>
#include <string>

#include "render/render_command.h"
#include "cli/commands.h"
#include "cli/progress.h"
#include "cli/service_options.h"
#include "core/sampling/samplers.h"

namespace alignset::cli {
namespace {

struct RenderOptions {
  render::RenderRequest request;
  std::string orientation = "normal";
  int64_t spp = 0;
  int64_t size = 128;
  int64_t seed = 1;
  ServiceOptions service;
  std::string reuse = "auto";
  std::string lattices = "local";
};

std::string SamplerHelp() {
  std::string s = "samplers:\n  the kinds of `alignset sample --list`:";
  for (const std::string& n : SamplerNames()) s += " " + n;
  s += "\n  pmj02bn-sheared, pmj02bn-sheared-exact  pmj02bn sheared to the pixel's estimated / exact θ\n"
       "  screen-space-rank1   rank-1 lattice, per-pixel shifts optimized as blue noise\n"
       "                       (Belcour and Heitz, screen-space samplers with blue-noise error)\n"
       "  aligned              aligned sets from the server for the pixel's θ estimated by\n"
       "                       core/analysis's EstimateDirection on a --prepass of the pixel\n"
       "  aligned-exact        aligned sets for θ from the scene's geometry (the bound)\n"
       "  aligned-lattice, aligned-lattice-exact  as aligned / aligned-exact, with aligned rank-1\n"
       "                       lattices chosen locally for each served θ (no server)\n"
       "  aligned-tent-lattice, aligned-tent-lattice-exact  the same lattices tent-folded after\n"
       "                       each pixel's shift (smooth shading integrated far better)\n"
       "  line, segment        line / segment samples (Singh, Miller and Jarosz, \"Variance and\n"
       "                       Convergence Analysis of Monte Carlo Line and Segment Sampling\"),\n"
       "                       --orientation\n";
  return s;
}

int Run(RenderOptions& o) {
  const bool sampler_given = !o.request.sampler.empty();
  if (!o.request.reference && (!sampler_given || o.spp < 1)) {
    return ReportError("render", Status::InvalidArgument("give --sampler NAME and --spp N, or --reference"),
                       kExitUsage);
  }
  if (o.request.reference && sampler_given) {
    return ReportError("render", Status::InvalidArgument("--reference writes the exact image; it takes no --sampler"),
                       kExitUsage);
  }
  if (o.orientation == "normal") {
    o.request.orientation = render::LineOrientation::kNormal;
  } else if (o.orientation == "edge") {
    o.request.orientation = render::LineOrientation::kEdge;
  } else {
    o.request.orientation = render::LineOrientation::kRandom;
  }
  o.request.spp = static_cast<uint32_t>(o.spp);
  o.request.reuse_prepass = *render::ParsePrepassReuse(o.reuse);  // checked by the option
  o.request.size = static_cast<int>(o.size);
  o.request.seed = static_cast<uint64_t>(o.seed);
  o.request.lattices_from_server = o.lattices == "server";
  if (o.request.sampler == "aligned" || o.request.sampler == "aligned-exact" || o.request.lattices_from_server) {
    auto connect = ResolveConnectOptions(o.service);
    if (!connect.ok()) return ReportError("render", connect.status(), kExitUsage);
    o.request.server = *connect;
  }
  std::map<std::string, std::unique_ptr<Progress>> bars;
  auto summary = render::RunRender(o.request, [&](const std::string& stage, double done, double total,
                                                  const std::string& detail) {
    auto& bar = bars[stage];
    if (!bar) bar = std::make_unique<Progress>(stage);
    bar->Update(done, total, detail);
  });
  for (auto& [stage, bar] : bars) bar->Finish("");
  if (!summary.ok()) {
    const bool usage = summary.status().code() == Status::Code::kInvalidArgument;
    return ReportError("render", summary.status(), usage ? kExitUsage : kExitFailure);
  }
  if (o.request.reference) {
    std::printf("wrote %s: %s, %lldx%lld, the exact image\n", o.request.out.c_str(),
                o.request.scene.c_str(), static_cast<long long>(o.size), static_cast<long long>(o.size));
    return kExitOk;
  }
  std::printf("wrote %s: %s, %lldx%lld, %s, N = %u\n", o.request.out.c_str(), o.request.scene.c_str(),
              static_cast<long long>(o.size), static_cast<long long>(o.size), o.request.sampler.c_str(),
              o.request.spp);
  if (summary->prepass_per_pixel > 0) {
    std::printf("samples per pixel: %u + %u pre-pass%s = %u\n", summary->samples_per_pixel,
                summary->prepass_per_pixel, summary->prepass_reused ? " (reused in the estimate)" : "",
                summary->total_per_pixel());
  } else {
    std::printf("samples per pixel: %u\n", summary->samples_per_pixel);
  }
  std::printf("MSE against the exact image: edge pixels %.4g, smooth pixels %.4g, all %.4g\n",
              summary->mse_edge, summary->mse_smooth, summary->mse_all);
  if (!summary->note.empty()) std::printf("%s\n", summary->note.c_str());
  std::printf("%.2f s\n", summary->seconds);
  return kExitOk;
}

}  // namespace

void AddRenderCommand(CLI::App& app) {
  auto o = std::make_shared<RenderOptions>();
  CLI::App* c = AddCommand(app, "render",
                           "render a test scene with one sampler into a .npy image (row y = pixel row y)");
  c->add_option("--scene", o->request.scene, "antialias | shadow")
      ->capture_default_str()
      ->check(CLI::IsMember({"antialias", "shadow"}));
  c->add_option("--sampler", o->request.sampler, "sampler name (listed below)");
  c->add_option("-n,--spp", o->spp, "samples per pixel")->check(IntegerIn(1, 65536));
  c->add_option("-o,--out", o->request.out, "output .npy (float64, shape (H, W))")->required();
  c->add_flag("--reference", o->request.reference, "write the exact image instead");
  c->add_option("--size", o->size, "image width and height in pixels")
      ->capture_default_str()
      ->check(IntegerIn(1, 4096));
  c->add_option("-s,--seed", o->seed, "scene and sampler seed")->capture_default_str()->check(IntegerIn(0, INT64_MAX));
  c->add_option("--orientation", o->orientation, "line / segment direction: normal | edge | random")
      ->capture_default_str()
      ->check(CLI::IsMember({"normal", "edge", "random"}));
  c->add_option("--segment-length", o->request.segment_length, "segment length in pixel widths")
      ->capture_default_str()
      ->check(FiniteIn(1e-6, 1.0));
  c->add_option("--prepass", o->request.prepass,
                 "pre-pass of the direction estimator (aligned, aligned-lattice, pmj02bn-sheared, line, segment): "
                 "auto (nedgesM, M a quarter of N from 16 to 256, stacked 5 x 5 up to N = 1024, on a lattice up to\n"
                 "N = 1024 and, where the pixels share one domain, at every N), gridG, jgridG,\n"
                 "samplesM, edgesM or nedgesM (edgesM pooled with the neighbouring pixels' samples; sR after it:\n"
                 "on a shared domain, the (2R + 1)^2 pixels around, R from 1 to 4, default 1),\n"
                 "optionally cP (a confidence floor of P percent); a final l on samplesM, edgesM, nedgesM\n"
                 "takes the M samples on a shifted rank-1 lattice instead of Owen-Sobol points")
      ->capture_default_str();
  c->add_option("--reuse-prepass", o->reuse,
                 "fold the pre-pass's samples into each pixel's estimate: auto (when the pre-pass\n"
                 "allows it: samplesM, edgesM; a pixel without a direction continues the pre-pass's\n"
                 "Owen-Sobol sequence, or leaves a lattice pre-pass out), on (refuse a pre-pass that does not), unbiased (as on, but\n"
                 "count weights on every pixel: no selection bias, noisier smooth pixels), off")
      ->capture_default_str()
      ->check(CLI::IsMember({"auto", "on", "unbiased", "off"}));
  c->add_option("--lattice-window", o->request.lattice_window_deg,
                 "aligned-lattice*, aligned-tent-lattice*: degrees either side of a pixel's θ its\n"
                 "lattice is chosen for (default 1; tent 2)")
      ->check(FiniteIn(0.0, 10.0));
  c->add_option("--lattice-size-span", o->request.lattice_size_span,
                 "aligned-lattice* with local lattices: each key's lattice may have N - SPAN ... N points,\n"
                 "the size whose generator scores best for its directions (a pixel spends at most N;\n"
                 "the search costs SPAN + 1 times as much)")
      ->capture_default_str()
      ->check(IntegerIn(0, 1024));
  c->add_option("--lattices", o->lattices,
                 "aligned-lattice*, aligned-tent-lattice*: local (search here) or server (read the\n"
                 "lattices a server has chosen and cached, --server; the same image, no search per render)")
      ->capture_default_str()
      ->check(CLI::IsMember({"local", "server"}));
  c->add_option("--threads", o->request.threads, "render threads")->capture_default_str()->check(IntegerIn(1, 256));
  AddServiceOptions(c, &o->service);
  c->footer([] { return SamplerHelp(); });
  OnRun(c, [o] { return Run(*o); });
}

}  // namespace alignset::cli

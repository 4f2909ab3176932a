#include <cstdio>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "cli/commands.h"
#include "cli/patch_file.h"
#include "cli/point_file.h"
#include "cli/progress.h"
#include "cli/service_options.h"
#include "core/optimize/construction.h"

namespace alignset::cli {
namespace {

int Usage(const Status& s) { return ReportError("get", s, kExitUsage); }
int Failure(const Status& s) { return ReportError("get", s, kExitFailure); }

// Served angles as the server reports them exactly (30.25 on the
// quarter-degree grid, 30 on whole degrees).
std::string Join(const std::vector<double>& v) {
  std::string s;
  for (double d : v) {
    char buf[32];
    std::snprintf(buf, sizeof(buf), "%.6g", d);
    s += (s.empty() ? "" : ",") + std::string(buf);
  }
  return s;
}

struct GetOptions {
  int64_t n = 0;
  std::vector<double> dirs;
  // --from-patch FILE: the directions estimated from an integrand patch by
  // the server's EstimateDirection (--two: also the second direction).
  std::string from_patch;
  bool two = false;
  // One direction's grid: empty, the server's (--angle-step); "1" or "0.25".
  std::string angle_step;
  std::string out;
  bool quiet = false;
  int64_t realization = 0;
  // -m M: realizations r .. r + M - 1 in one batch call, as a multi-set file.
  std::optional<int64_t> sets;
  // --space 1dir: the whole one-direction space of N (the 46 canonical sets,
  // phi = 0..45) in one batch call, as (46, N, 2) .npy or 46 text sets.
  std::string space;
  // "optimized" (the default), "lattice" or "net": how the server makes the set.
  std::string construction = "optimized";
  ServiceOptions service;
};

// What a text file records about a served set, one '#' line or two.
std::string Comment(const SetInfo& i) {
  char comment[768];
  std::snprintf(comment, sizeof(comment),
                "alignset served set: N=%u directions(deg, edge normal)=0,90,%s key=%s "
                "realization=%u\nswap=%d invert=%d loss=%.9g spectrum=%.9g sw=%.9g iterations=%d "
                "engine=%s seed=%llu algorithm_version=%d construction=%s%s",
                i.n, Join(i.served_exact_deg).c_str(), i.key_text.c_str(), i.realization, i.swapped,
                i.inverted, i.loss_total, i.loss_spectrum, i.loss_sw, i.iterations, i.engine.c_str(),
                static_cast<unsigned long long>(i.seed), i.algorithm_version, i.construction.c_str(),
                i.lattice_generator != 0 ? (" generator=" + std::to_string(i.lattice_generator)).c_str() : "");
  return comment;
}

// SetRequest::steps_per_degree: 0 leaves the grid to the server.
uint32_t StepsPerDegree(const GetOptions& o) {
  return o.angle_step.empty() ? 0 : o.angle_step == "0.25" ? 4 : 1;
}

// One set through the streaming call, which shows queue position and
// optimization progress (a cache hit arrives as its only message).
StatusOr<AlignedSet> WatchOne(ServiceClient& client, const GetOptions& o) {
  Progress progress("optimize");
  bool shown = false;
  const SetRequest request{static_cast<uint32_t>(o.n), o.dirs,
                           static_cast<uint32_t>(o.realization), StepsPerDegree(o), o.construction};
  auto set = client.WatchAlignedSet(request, [&](const WatchUpdate& u) {
    if (o.quiet) return;
    shown = true;
    if (u.queued) {
      progress.Update(0, 1, "queued at position " + std::to_string(u.queue_position));
      return;
    }
    char detail[96];
    std::snprintf(detail, sizeof(detail), "loss %.5g lr %.2g", u.loss, u.learning_rate);
    progress.Update(u.iteration, u.max_iterations, detail);
  });
  if (set.ok() && shown) progress.Finish("");
  return set;
}

// Several realizations in one batch call: the server optimizes the missing
// ones in parallel.
StatusOr<std::vector<AlignedSet>> GetMany(ServiceClient& client, const GetOptions& o) {
  std::vector<SetRequest> items;
  for (int64_t i = 0; i < *o.sets; ++i) {
    items.push_back({static_cast<uint32_t>(o.n), o.dirs, static_cast<uint32_t>(o.realization + i),
                     StepsPerDegree(o), o.construction});
  }
  if (!o.quiet) {
    std::fprintf(stderr, "alignset get: %lld realizations (%lld..%lld) in one call\n",
                 static_cast<long long>(*o.sets), static_cast<long long>(o.realization),
                 static_cast<long long>(o.realization + *o.sets - 1));
  }
  auto batch = client.GetAlignedSets(items);
  if (!batch.ok()) return batch.status();
  std::vector<AlignedSet> sets;
  for (size_t i = 0; i < batch->size(); ++i) {
    BatchItem& item = (*batch)[i];
    if (!item.status.ok()) {
      return Status(item.status.code() == Status::Code::kInvalidArgument
                        ? Status::InvalidArgument("realization " + std::to_string(items[i].realization) +
                                                  ": " + item.status.message())
                        : Status::Unavailable("realization " + std::to_string(items[i].realization) +
                                              ": " + item.status.message()));
    }
    sets.push_back(std::move(item.set));
  }
  return sets;
}

std::string Degrees(double v) {
  char buf[32];
  std::snprintf(buf, sizeof(buf), "%.4f", v);
  return buf;
}

// --from-patch: the direction(s) to ask for, from the server's estimate. A
// patch without a dominant direction is a failure that says so: serving a set
// for an arbitrary angle would hide it.
StatusOr<std::vector<double>> DirectionsFromPatch(ServiceClient& client, const GetOptions& o,
                                                  bool* usage_error) {
  auto input = ReadPatchFile(o.from_patch);
  if (!input.ok()) {
    *usage_error = true;
    return input.status();
  }
  auto reply = input->is_grid
                   ? client.EstimateDirection(input->grid.width, input->grid.height,
                                              input->grid.values, o.two)
                   : client.EstimateDirection(input->samples.points, input->samples.values, o.two);
  if (!reply.ok()) return reply.status();
  if (!reply->first.found) {
    return Status::InvalidArgument(o.from_patch + ": no dominant direction (" + reply->first.reason +
                                   "); give --dir instead");
  }
  std::vector<double> dirs = {reply->first.theta_deg};
  if (o.two) {
    if (!reply->has_second || !reply->second.found) {
      return Status::InvalidArgument(o.from_patch + ": no second direction (" +
                                     reply->second.reason + "); drop --two");
    }
    dirs.push_back(reply->second.theta_deg);
  }
  if (!o.quiet) {
    std::string also = dirs.size() == 2 ? ", theta2 " + Degrees(dirs[1]) : "";
    std::fprintf(stderr, "alignset get: %s: estimated theta %s%s (kappa %.4g, confidence %.3f)\n",
                 o.from_patch.c_str(), Degrees(dirs[0]).c_str(), also.c_str(), reply->first.kappa,
                 reply->first.confidence);
  }
  return dirs;
}

// The one-direction space: what a table-driven renderer loads once and
// aligns itself (method.md, Algorithm 1).
int RunGetSpace(const GetOptions& o) {
  if (!o.dirs.empty() || !o.from_patch.empty() || o.sets || !o.angle_step.empty()) {
    return Usage(Status::InvalidArgument(
        "--space 1dir takes no --dir, --from-patch, -m or --angle-step (it is the 46 canonical sets)"));
  }
  auto client = Connect(o.service);
  if (!client.ok()) return Usage(client.status());
  if (!o.quiet) {
    std::fprintf(stderr, "alignset get: the one-direction space of N = %lld (46 sets) in one call\n",
                 static_cast<long long>(o.n));
  }
  auto batch = (*client)->GetOneDirectionSpace(static_cast<uint32_t>(o.n),
                                               static_cast<uint32_t>(o.realization), o.construction);
  if (!batch.ok()) return Failure(batch.status());
  std::vector<PointSet> points;
  std::string comment = "alignset one-direction space: set k is the canonical set for phi = k deg "
                        "(k = 0..45); other directions by Algorithm 1 (swap / invert)";
  for (size_t k = 0; k < batch->size(); ++k) {
    BatchItem& item = (*batch)[k];
    if (!item.status.ok()) return Failure(Status::Unavailable("phi = " + std::to_string(k) + ": " + item.status.message()));
    comment += "\n" + Comment(item.set.info);
    points.push_back(std::move(item.set.points));
  }
  if (Status written = WritePointSets(o.out, points, comment); !written.ok()) return Failure(written);
  FILE* report = ReportStreamFor(o.out);
  std::fprintf(report, "wrote %s: %zu sets of %lld points (phi = 0..45 deg), realization %lld\n",
               o.out.c_str(), points.size(), static_cast<long long>(o.n),
               static_cast<long long>(o.realization));
  return kExitOk;
}

int RunGet(GetOptions o) {
  if (!o.space.empty()) return RunGetSpace(o);
  if (o.dirs.empty() == o.from_patch.empty()) {
    return Usage(Status::InvalidArgument(
        "give --dir (degrees, edge normal) or --from-patch FILE, or --space 1dir"));
  }
  if (o.two && o.from_patch.empty()) {
    return Usage(Status::InvalidArgument("--two goes with --from-patch (with --dir, give it twice)"));
  }
  if (o.dirs.size() > 2) {
    return Usage(Status::InvalidArgument("give one or two --dir angles (degrees, edge normal), got " +
                                         std::to_string(o.dirs.size())));
  }
  if (o.sets && o.realization + *o.sets - 1 > SetRequest::kMaxRealization) {
    return Usage(Status::InvalidArgument(
        "realizations " + std::to_string(o.realization) + ".." +
        std::to_string(o.realization + *o.sets - 1) + " go past the maximum of " +
        std::to_string(SetRequest::kMaxRealization)));
  }
  auto client = Connect(o.service);
  if (!client.ok()) return Usage(client.status());
  if (!o.from_patch.empty()) {
    bool usage_error = false;
    auto dirs = DirectionsFromPatch(**client, o, &usage_error);
    if (!dirs.ok()) return usage_error ? Usage(dirs.status()) : Failure(dirs.status());
    o.dirs = std::move(dirs).value();
  }

  std::vector<AlignedSet> sets;
  if (o.sets) {
    auto many = GetMany(**client, o);
    if (!many.ok()) return Failure(many.status());
    sets = std::move(many).value();
  } else {
    auto one = WatchOne(**client, o);
    if (!one.ok()) return Failure(one.status());
    sets.push_back(std::move(one).value());
  }

  std::string comment;
  std::vector<PointSet> points;
  for (const AlignedSet& s : sets) {
    comment += (comment.empty() ? "" : "\n") + Comment(s.info);
    points.push_back(s.points);
  }
  const Status written = o.sets ? WritePointSets(o.out, points, comment)
                                : WritePointFile(o.out, points[0], comment);
  if (!written.ok()) return Failure(written);

  FILE* report = ReportStreamFor(o.out);
  const SetInfo& i = sets[0].info;
  std::fprintf(report, "N              %u\n", i.n);
  std::fprintf(report, "directions     0, 90, %s (served; deg, spectral = edge normal)\n",
               Join(i.served_exact_deg).c_str());
  std::fprintf(report, "canonical key  %s (index %llu)\n", i.key_text.c_str(),
               static_cast<unsigned long long>(i.key_index));
  std::fprintf(report, "alignment      swap %s, invert x %s\n", i.swapped ? "yes" : "no",
               i.inverted ? "yes" : "no");
  for (const AlignedSet& s : sets) {
    const SetInfo& si = s.info;
    if (o.sets) std::fprintf(report, "realization    %u (seed %llu)\n", si.realization,
                             static_cast<unsigned long long>(si.seed));
    const Construction* made = FindConstruction(si.construction);
    if (made != nullptr && !made->optimized()) {
      std::fprintf(report, "construction   aligned %s, %.3f s, profile %s\n",
                   std::string(made->description).c_str(), si.optimize_seconds, si.profile.c_str());
      if (si.lattice_generator != 0) {
        std::fprintf(report, "generator      (1, %u) / %u%s\n", si.lattice_generator, si.n,
                     made->folded() ? ", shifted then folded" : "");
      }
    } else {
      std::fprintf(report, "loss           %.6g (spectrum %.6g, SW %.6g)\n", si.loss_total,
                   si.loss_spectrum, si.loss_sw);
      std::fprintf(report, "optimization   %d iterations, %.2f s, engine %s, profile %s\n",
                   si.iterations, si.optimize_seconds, si.engine.c_str(), si.profile.c_str());
    }
    std::fprintf(report, "from cache     %s\n", si.from_cache ? "yes" : "no");
  }
  std::fprintf(report, "wrote          %s\n", o.out.c_str());
  return kExitOk;
}

}  // namespace

void AddGetCommand(CLI::App& app) {
  auto o = std::make_shared<GetOptions>();
  CLI::App* c = AddCommand(app, "get",
                           "an aligned set from alignset-server (.npy or UTK text by extension)");
  // The server checks N against its own maximum; here only the type.
  c->add_option("-n,--n", o->n, "number of points")->required()->check(PointCount());
  CLI::Option* dir =
      c->add_option("--dir", o->dirs, "direction in degrees (edge normal), once or twice")
          ->allow_extra_args(false)
          ->check(FiniteNumber());
  c->add_option("--from-patch", o->from_patch,
                "estimate the direction from an integrand patch first (as `alignset direction`\n"
                "reads it: .npy (H, W) grid or 'x y f' text) and ask for that")
      ->excludes(dir);
  c->add_flag("--two", o->two, "with --from-patch: the two strongest directions (4-direction set)");
  c->add_option("-o,--out", o->out, "output file: UTK text, .npy, .csv by extension; - stdout")
      ->required();
  c->add_option("-r,--realization", o->realization,
                "which of the key's independent sets (0 .. 63; 0: the key's first)")
      ->capture_default_str()
      ->check(IntegerIn(0, SetRequest::kMaxRealization));
  c->add_option("-m,--sets", o->sets,
                "several realizations, R .. R+M-1, in one call: '#'-separated text, (m, N, 2) .npy")
      ->check(IntegerIn(1, SetRequest::kMaxRealization + 1));
  c->add_option("--space", o->space,
                 "instead of --dir: the whole one-direction space, the 46 canonical sets\n"
                 "phi = 0..45 ((46, N, 2) .npy; a table for a renderer that aligns itself)")
      ->check(CLI::IsMember({"1dir"}));
  c->add_option("--angle-step", o->angle_step,
                "grid one direction is served on: 0.25 or 1 degree (default: the server's)")
      ->check(CLI::IsMember({"1", "0.25"}));
  c->add_option("--construction", o->construction,
                "optimized (the server's optimized sets), lattice (an aligned rank-1\n"
                "lattice), tent-lattice (the lattice folded by 1 - |2u - 1| after its shift)\n"
                "net (an aligned (0,m,2)-net, N a power of two) or lattice-sequence (the\n"
                "first N points of an aligned lattice sequence: a pixel may stop after any\n"
                "prefix); each cached apart from the others")
      ->capture_default_str()
      ->check(ConstructionName());
  c->add_flag("-q,--quiet", o->quiet, "no progress display");
  AddServiceOptions(c, &o->service);
  OnRun(c, [o] { return RunGet(*o); });
}

}  // namespace alignset::cli

// `alignset export`: the table file a renderer loads (<alignset/set_table.h>),
// written from a cache file the server filled (precompute first). The server
// stays the factory; the table is what a render-farm node ships.
#include <alignset/set_table.h>

#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "cli/commands.h"
#include "cli/progress.h"
#include "cli/table_space.h"
#include "cli/table_summary.h"
#include "core/align/canonical.h"
#include "core/optimize/aligned_lattice.h"
#include "core/optimize/construction.h"
#include "core/optimize/optimizer.h"
#include "core/optimize/point_count.h"
#include "storage/paths.h"
#include "storage/set_cache.h"

namespace alignset::cli {
namespace {

struct ExportOptions {
  std::string db;
  std::vector<uint32_t> n;
  std::vector<std::string> constructions = {"lattice"};
  std::vector<std::string> spaces = {"1dir"};
  std::string profile;  // the optimized sets' profile; empty: the server's default
  uint64_t seed = 1;    // the server's --seed, for that default profile
  std::string out;
};

// One section from the cache: realization 0 of every key of the space.
StatusOr<TableSection> ReadSection(storage::SetCache& cache, const ExportOptions& o, uint32_t n,
                                   const Construction& c, TableSpace space) {
  TableSection s;
  s.n = n;
  s.construction = std::string(c.name);
  s.space = space;
  const SpaceShape shape = ShapeOf(space);
  const int count = shape.directions;
  const AngleGrid grid = shape.grid;
  const std::string profile = c.optimized() && !o.profile.empty() ? o.profile
                                                                 : storage::KeyProfile(n, c, OptimizerOptions{}, o.seed);
  const size_t keys = CanonicalKeyCount(count, grid);
  size_t missing = 0;
  std::string first_missing;
  for (size_t i = 0; i < keys; ++i) {
    const storage::SetKey key{n, CanonicalKeyAt(count, i, grid), profile, 0};
    auto rec = cache.Get(key);
    if (!rec.ok()) {
      if (rec.status().code() != Status::Code::kNotFound) {
        return Status(rec.status().code() == Status::Code::kDataLoss
                          ? Status::DataLoss(storage::KeyToString(key) + ": " + rec.status().message())
                          : Status::Internal(storage::KeyToString(key) + ": " + rec.status().message()));
      }
      if (missing++ == 0) first_missing = storage::KeyToString(key);
      continue;
    }
    if (c.lattice()) {
      auto g = LatticeGeneratorOf(rec->points, 0, c.folded());
      if (!g) return Status::DataLoss(storage::KeyToString(key) + ": the stored points are no lattice");
      s.generators.push_back(*g);
    } else {
      s.sets.push_back(std::move(rec->points));
    }
  }
  if (missing > 0) {
    return Status::NotFound("N=" + std::to_string(n) + " " + s.construction + " " + TableSpaceName(space) + ": " +
                            std::to_string(missing) + " of " + std::to_string(keys) +
                            " keys are not in the cache (the first: " + first_missing +
                            "); fill them first: alignset precompute --n " + std::to_string(n) + " --space " +
                            (count == 2 ? "2dir" : "1dir") + (grid == AngleGrid::kQuarterDegree ? " --angle-step 0.25" : "") +
                            " --construction " + s.construction +
                            (c.optimized() ? " (optimized sets are keyed by the server's settings: give --profile "
                                             "if it runs other ones than the defaults)"
                                           : ""));
  }
  return s;
}

int RunExport(const ExportOptions& in) {
  ExportOptions o = in;
  if (o.db.empty()) {
    auto path = storage::DefaultDatabasePath();
    if (!path.ok()) return ReportError("export", path.status(), kExitFailure);
    o.db = *path;
  }
  if (!std::filesystem::exists(o.db)) {
    return ReportError("export", Status::NotFound(o.db + " does not exist (start the server, precompute, then export)"),
                       kExitUsage);
  }
  auto parsed = ParseTableSpaces(o.spaces);
  if (!parsed.ok()) return ReportError("export", parsed.status(), kExitUsage);
  const std::vector<TableSpace>& spaces = *parsed;
  storage::SetCache::Options co;
  co.read_only = true;
  auto cache = storage::SetCache::Open(o.db, co);
  if (!cache.ok()) return ReportError("export", cache.status(), kExitFailure);
  std::vector<TableSection> sections;
  Progress progress("export");
  const double total = static_cast<double>(o.n.size() * o.constructions.size() * spaces.size());
  for (uint32_t n : o.n) {
    for (const std::string& name : o.constructions) {
      const Construction& c = *FindConstruction(name);
      if (Status size = ValidatePointCount(n, c); !size.ok()) return ReportError("export", size, kExitUsage);
      for (TableSpace space : spaces) {
        auto s = ReadSection(**cache, o, n, c, space);
        if (!s.ok()) return ReportError("export", s.status(), kExitFailure);
        sections.push_back(std::move(s).value());
        progress.Update(static_cast<double>(sections.size()), total,
                        "N=" + std::to_string(n) + " " + name + " " + TableSpaceName(space));
      }
    }
  }
  progress.Finish("");
  auto table = SetTable::FromSections(std::move(sections));
  if (!table.ok()) return ReportError("export", table.status(), kExitFailure);
  if (Status saved = (*table)->Save(o.out); !saved.ok()) return ReportError("export", saved, kExitFailure);
  PrintTableSummary(**table, o.out);
  return kExitOk;
}

}  // namespace

void AddExportCommand(CLI::App& app) {
  auto o = std::make_shared<ExportOptions>();
  CLI::App* c = AddCommand(app, "export",
                           "write the table file a renderer loads (<alignset/set_table.h>) from a cache:\n"
                           "realization 0 of every key of each space, N and construction; a lattice as its\n"
                           "generator, any other set as its points. No server at render time.");
  c->add_option("--db", o->db, "the cache file (default: the server's, ~/.local/share/alignset/alignset.sqlite)");
  c->add_option("-n,--n", o->n, "point counts, comma-separated (e.g. 256,1024)")
      ->required()
      ->delimiter(',')
      ->check(PointCount());
  c->add_option("--construction", o->constructions,
                "constructions, comma-separated: lattice (default), tent-lattice, optimized, net,\n"
                "lattice-sequence (stored as points: export the largest N a pixel may reach)")
      ->delimiter(',')
      ->check(ConstructionName());
  c->add_option("--space", o->spaces, "key spaces, comma-separated: 1dir (default; 46 keys), 1dir-quarter (181), 2dir (4141)")
      ->delimiter(',');
  c->add_option("--profile", o->profile, "the optimized sets' profile id (default: the server's default profile)");
  c->add_option("--seed", o->seed, "the server's --seed, for its default profile")->check(SeedValue());
  c->add_option("-o,--out", o->out, "the table file")->required();
  OnRun(c, [o] { return RunExport(*o); });
}

}  // namespace alignset::cli

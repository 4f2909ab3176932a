// `alignset table`: the table file a renderer loads (<alignset/set_table.h>)
// for the constructions core builds without the optimizer (lattice,
// tent-lattice, lattice-sequence, net), searched here with the same core search the server runs
// for a key (Construction::Build of the key's exact angles, realization 0),
// so the file equals `alignset export` of a server's cache byte for byte.
// No server, no SQLite: a render-farm node or a renderer's build makes its
// table with the command line alone. The optimized sets stay the server's
// to make (minutes a key, keyed by its settings; `alignset export` writes
// them from its cache).
#include <alignset/set_table.h>

#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "cli/commands.h"
#include "cli/progress.h"
#include "cli/table_space.h"
#include "cli/table_summary.h"
#include "core/align/canonical.h"
#include "core/optimize/construction.h"
#include "core/optimize/lattice_term_cache.h"
#include "core/optimize/point_count.h"

namespace alignset::cli {
namespace {

struct TableOptions {
  std::vector<uint32_t> n;
  std::vector<std::string> constructions = {"lattice"};
  std::vector<std::string> spaces = {"1dir"};
  int64_t threads = 0;
  std::string out;
};

// One section: every canonical key of the space built as the server builds a
// missing key (its exact angles, realization 0); a lattice kept as its
// generator, a lattice sequence or a net as its N points (what `export`
// stores).
StatusOr<TableSection> BuildSection(uint32_t n, const Construction& c, TableSpace space,
                                    const ConstructionContext& context, Progress& progress, double& done,
                                    double total) {
  TableSection s;
  s.n = n;
  s.construction = std::string(c.name);
  s.space = space;
  const SpaceShape shape = ShapeOf(space);
  const size_t keys = CanonicalKeyCount(shape.directions, shape.grid);
  for (size_t i = 0; i < keys; ++i) {
    const CanonicalDirections key = CanonicalKeyAt(shape.directions, i, shape.grid);
    std::vector<double> dirs = {Phi1Degrees(key)};
    if (key.count == 2) dirs.push_back(Phi2Degrees(key));
    auto made = c.Build(n, dirs, 0, context);
    if (!made.ok()) return made.status();
    if (c.lattice()) {
      s.generators.push_back(made->lattice_generator);
    } else {
      s.sets.push_back(std::move(made->points));
    }
    done += 1.0;
    progress.Update(done, total, "N=" + std::to_string(n) + " " + s.construction + " " + TableSpaceName(space));
  }
  return s;
}

int RunTable(const TableOptions& o) {
  auto parsed = ParseTableSpaces(o.spaces);
  if (!parsed.ok()) return ReportError("table", parsed.status(), kExitUsage);
  const std::vector<TableSpace>& spaces = *parsed;
  std::vector<const Construction*> constructions;
  for (const std::string& name : o.constructions) {
    const Construction& c = *FindConstruction(name);
    if (c.optimized()) {
      return ReportError("table",
                         Status::InvalidArgument("construction '" + name +
                                                 "' is made by the server: precompute it there, then "
                                                 "alignset export --construction " + name),
                         kExitUsage);
    }
    for (uint32_t n : o.n) {
      if (Status size = ValidatePointCount(n, c); !size.ok()) return ReportError("table", size, kExitUsage);
    }
    constructions.push_back(&c);
  }
  double total = 0.0;
  for (TableSpace space : spaces) {
    const SpaceShape shape = ShapeOf(space);
    total += static_cast<double>(CanonicalKeyCount(shape.directions, shape.grid));
  }
  total *= static_cast<double>(o.n.size() * constructions.size());

  LatticeTermCache terms;  // shared between keys and sizes, as a server's
  ConstructionContext context;
  context.threads = o.threads > 0 ? static_cast<int>(o.threads)
                                  : std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
  context.lattice_terms = &terms;
  std::vector<TableSection> sections;
  Progress progress("table");
  double done = 0.0;
  for (uint32_t n : o.n) {
    for (const Construction* c : constructions) {
      for (TableSpace space : spaces) {
        auto s = BuildSection(n, *c, space, context, progress, done, total);
        if (!s.ok()) return ReportError("table", s.status(), kExitFailure);
        sections.push_back(std::move(s).value());
      }
    }
  }
  progress.Finish("");
  auto table = SetTable::FromSections(std::move(sections));
  if (!table.ok()) return ReportError("table", table.status(), kExitFailure);
  if (Status saved = (*table)->Save(o.out); !saved.ok()) return ReportError("table", saved, kExitFailure);
  PrintTableSummary(**table, o.out);
  return kExitOk;
}

}  // namespace

void AddTableCommand(CLI::App& app) {
  auto o = std::make_shared<TableOptions>();
  CLI::App* c = AddCommand(app, "table",
                           "write the table file a renderer loads (<alignset/set_table.h>) for lattices,\n"
                           "searched here as the server searches them (no server, no cache): every key of\n"
                           "each space, N and construction, equal to `export` of a server's cache.");
  c->add_option("-n,--n", o->n, "point counts, comma-separated (e.g. 256,1024)")
      ->required()
      ->delimiter(',')
      ->check(PointCount());
  c->add_option("--construction", o->constructions,
                "constructions, comma-separated: lattice (default), tent-lattice, lattice-sequence,\n"
                "net (the optimized sets come from a server: alignset export)")
      ->delimiter(',')
      ->check(ConstructionName());
  c->add_option("--space", o->spaces, "key spaces, comma-separated: 1dir (default; 46 keys), 1dir-quarter (181), 2dir (4141)")
      ->delimiter(',');
  c->add_option("-j,--threads", o->threads, "threads of each key's search (default: every core)")
      ->check(IntegerIn(0, 1024));
  c->add_option("-o,--out", o->out, "the table file")->required();
  OnRun(c, [o] { return RunTable(*o); });
}

}  // namespace alignset::cli

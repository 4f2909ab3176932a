#pragma once

#include "cli/cli_app.h"

namespace alignset::cli {

// Each Add*Command registers one subcommand of `alignset` on `app`: its
// options (CLI11) and the callback that runs it. A failing run prints one
// line "alignset <command>: <message>" on stderr and ends with Finish(status).
void AddOptimizeCommand(CLI::App& app);
void AddEvaluateCommand(CLI::App& app);
void AddSampleCommand(CLI::App& app);
void AddAlignCommand(CLI::App& app);
void AddVarianceCommand(CLI::App& app);
// Expected power spectra and their profiles (analyze), variance against N
// (convergence); PNGs through scripts/plot_analysis.py (cli/plot_script.h).
void AddAnalyzeCommand(CLI::App& app);
void AddConvergenceCommand(CLI::App& app);
// The principal direction of an integrand patch (core/analysis).
void AddDirectionCommand(CLI::App& app);
// The joint lattice a renderer's pixel gets (cli/cmd_joint.cc).
void AddJointCommand(CLI::App& app);
// The table file of lattices, searched here without a server (cli/cmd_table.cc).
void AddTableCommand(CLI::App& app);
#ifdef ALIGNSET_HAVE_STORAGE
// export / import / merge / verify / list of SQLite cache files.
void AddCacheCommand(CLI::App& app);
void AddExportCommand(CLI::App& app);
#endif
#ifdef ALIGNSET_HAVE_SERVICE
// Clients of alignset-server (client/service_client.h).
void AddGetCommand(CLI::App& app);
void AddPrecomputeCommand(CLI::App& app);
void AddStatsCommand(CLI::App& app);
#endif
#ifdef ALIGNSET_HAVE_RENDER
// `alignset render` (cli/cmd_render.cc, on the renderer library render/):
// built with the client library.
void AddRenderCommand(CLI::App& app);
#endif

}  // namespace alignset::cli

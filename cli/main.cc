// alignset: the command line. Local subcommands use core directly; the
// service subcommands talk to alignset-server (client/service_client.h).
#include "cli/cli_app.h"
#include "cli/commands.h"

#ifdef ALIGNSET_HAVE_STORAGE
#include "storage/profile.h"
#endif

namespace {

std::string Version() {
#ifdef ALIGNSET_HAVE_STORAGE
  return alignset::storage::VersionText("alignset", ALIGNSET_VERSION);
#else
  return std::string("alignset ") + ALIGNSET_VERSION + " (built without storage: no profile)";
#endif
}

}  // namespace

int main(int argc, char** argv) {
  using namespace alignset::cli;
  CLI::App app("Optimized, direction-aligned anisotropic sampling point sets.\n"
               "Angles are degrees and name the spectral direction: the normal of the edge.",
               "alignset");
  app.set_version_flag("-V,--version", Version());
  app.footer(kExitStatusHelp);  // inherited by every subcommand
  app.require_subcommand(1);
  AddOptimizeCommand(app);
  AddEvaluateCommand(app);
  AddSampleCommand(app);
  AddAlignCommand(app);
  AddVarianceCommand(app);
  AddAnalyzeCommand(app);
  AddConvergenceCommand(app);
  AddDirectionCommand(app);
#ifdef ALIGNSET_HAVE_STORAGE
  AddCacheCommand(app);
  AddExportCommand(app);
#endif
#ifdef ALIGNSET_HAVE_SERVICE
  AddGetCommand(app);
  AddPrecomputeCommand(app);
  AddStatsCommand(app);
#endif
#ifdef ALIGNSET_HAVE_RENDER
  AddRenderCommand(app);
#endif
  return RunApp(app, argc, argv);
}

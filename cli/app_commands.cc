#include "cli/app_commands.h"

#include <string>

#include "cli/commands.h"

#ifdef ALIGNSET_HAVE_STORAGE
#include "storage/profile.h"
#endif

namespace alignset::cli {
namespace {

std::string Version() {
#ifdef ALIGNSET_HAVE_STORAGE
  return alignset::storage::VersionText("alignset", ALIGNSET_VERSION);
#else
  return std::string("alignset ") + ALIGNSET_VERSION + " (built without storage: no profile)";
#endif
}

}  // namespace

void AddEveryCommand(CLI::App& app) {
  app.description("Optimized, direction-aligned anisotropic sampling point sets.\n"
                  "Angles are degrees and name the spectral direction: the normal of the edge.");
  app.name("alignset");
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
  AddTableCommand(app);
  AddJointCommand(app);
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
}

}  // namespace alignset::cli

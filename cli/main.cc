// alignset: the command line. Local subcommands use core directly; the
// service subcommands talk to alignset-server (client/service_client.h).
#include "cli/app_commands.h"

int main(int argc, char** argv) {
  CLI::App app;
  alignset::cli::AddEveryCommand(app);
  return alignset::cli::RunApp(app, argc, argv);
}

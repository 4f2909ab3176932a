#pragma once

#include <string>

#include "core/util/status.h"

namespace alignset::cli {

// Exit statuses: bad input or a failed local step, and a failed call to the
// service (the server's answer is in the message).
inline constexpr int kExitUsage = 2;
inline constexpr int kExitService = 1;

// Prints `s` as the one error line "alignset <command>: <message>" on stderr
// and returns `exit_code`.
int ReportError(const std::string& command, const Status& s, int exit_code);

// Each subcommand takes the arguments after its name and returns the process
// exit status; errors are printed as one line on stderr.
int RunOptimize(int argc, char** argv);
int RunEvaluate(int argc, char** argv);
int RunSample(int argc, char** argv);
int RunAlign(int argc, char** argv);
int RunVariance(int argc, char** argv);
#ifdef ALIGNSET_HAVE_STORAGE
// export / import / merge / verify / list of SQLite cache files.
int RunCache(int argc, char** argv);
#endif
#ifdef ALIGNSET_HAVE_SERVICE
// Clients of alignset-server (client/service_client.h).
int RunGet(int argc, char** argv);
int RunPrecompute(int argc, char** argv);
int RunStats(int argc, char** argv);
#endif

}  // namespace alignset::cli

// alignset-server: serves aligned point sets over gRPC (see server/server.h).
#include <signal.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <thread>

#include "server/config.h"
#include "server/process_memory.h"
#include "server/server.h"
#include "storage/profile.h"

#if defined(ALIGNSET_WITH_JEMALLOC)
// jemalloc's options, read at its start: a thread of its own purges freed
// pages on their 10 s decay even while the server is idle (otherwise purging
// waits for the next allocation).
extern "C" const char* malloc_conf = "background_thread:true";
#endif

int main(int argc, char** argv) {
  // Before any thread: the cap applies to the arenas threads create. One
  // arena a core (glibc's default is eight), two at least.
  const std::string allocator_note =
      alignset::server::LimitAllocatorKeeping(std::max(2, static_cast<int>(std::thread::hardware_concurrency())));
  // --version wins over every other flag, as --help does.
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--version") || !std::strcmp(argv[i], "-V")) {
      std::puts(alignset::storage::VersionText("alignset-server", ALIGNSET_VERSION).c_str());
      return 0;
    }
  }
  auto config = alignset::server::ParseServerConfig(argc - 1, argv + 1, [](const char* name) {
    return static_cast<const char*>(std::getenv(name));
  });
  if (!config.ok()) {
    if (config.status().code() == alignset::Status::Code::kNotFound) {  // --help
      std::fputs(config.status().message().c_str(), stdout);
      return 0;
    }
    std::fprintf(stderr, "alignset-server: %s\n", config.status().message().c_str());
    return 2;
  }
  auto level = spdlog::level::from_str(config->log_level);
  if (level == spdlog::level::off && config->log_level != "off") {
    std::fprintf(stderr, "alignset-server: unknown --log-level '%s'\n", config->log_level.c_str());
    return 2;
  }
  spdlog::set_level(level);
  spdlog::set_pattern("%Y-%m-%dT%H:%M:%S.%e %^%l%$ %v");
  if (!allocator_note.empty()) spdlog::info("{}", allocator_note);

  // Block the stop signals in every thread (they inherit the mask) and take
  // them synchronously here, so shutdown runs in ordinary code.
  sigset_t stop;
  sigemptyset(&stop);
  sigaddset(&stop, SIGTERM);
  sigaddset(&stop, SIGINT);
  pthread_sigmask(SIG_BLOCK, &stop, nullptr);
  signal(SIGPIPE, SIG_IGN);

  auto server = alignset::server::ServerInstance::Start(*config);
  if (!server.ok()) {
    std::fprintf(stderr, "alignset-server: %s\n", server.status().message().c_str());
    return 1;
  }
  int sig = 0;
  sigwait(&stop, &sig);
  spdlog::info("received {}", sig == SIGTERM ? "SIGTERM" : "SIGINT");
  (*server)->Shutdown(config->shutdown_grace_seconds);
  // Everything that must reach the disk has: the workers are joined and the
  // cache closed (a WAL checkpoint). gRPC's own teardown at exit joins an
  // executor thread that can sit in a poll of up to 10 s after connections
  // were closed under a transfer that had just finished (a server stopped
  // in 1 s exited 11 s after SIGTERM in 4 of 10 runs of the e2e test), so
  // the process leaves without it.
  spdlog::shutdown();
  std::fflush(nullptr);
  std::_Exit(0);
}

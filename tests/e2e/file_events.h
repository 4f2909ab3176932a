#pragma once

#include <sys/types.h>

#include <chrono>
#include <cstdint>
#include <functional>
#include <string>

namespace alignset::e2e {

enum class WaitEnd { kReady, kExited, kTimeout };

// Waits on events, not on a clock: `ready()` is asked now and after every
// inotify event `mask` reports on `path` (a file, or a folder for files that
// appear in it), until it holds (kReady), the process `pid` exits (kExited;
// pid <= 0: none is watched), or `timeout` passes (kTimeout). A server's port
// file and log lines are what the end-to-end tests wait for this way.
WaitEnd WaitForFileEvent(const std::string& path, uint32_t mask, pid_t pid, const std::function<bool()>& ready,
                         std::chrono::milliseconds timeout);

}  // namespace alignset::e2e

#include "tests/e2e/file_events.h"

#include <poll.h>
#include <sys/inotify.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>

namespace alignset::e2e {
namespace {

// Closes a descriptor on scope exit.
struct Fd {
  int fd = -1;
  ~Fd() {
    if (fd >= 0) close(fd);
  }
};

}  // namespace

WaitEnd WaitForFileEvent(const std::string& path, uint32_t mask, pid_t pid, const std::function<bool()>& ready,
                         std::chrono::milliseconds timeout) {
  using Clock = std::chrono::steady_clock;
  const auto end = Clock::now() + timeout;
  Fd events{inotify_init1(IN_NONBLOCK | IN_CLOEXEC)};
  // Watched before the first look, so that nothing happens unseen between them.
  if (events.fd >= 0 && inotify_add_watch(events.fd, path.c_str(), mask) < 0) {
    close(events.fd);
    events.fd = -1;
  }
  // The process's exit as an event too (Linux 5.3's pidfd; glibc 2.36 has no wrapper).
  Fd exited{pid > 0 ? static_cast<int>(syscall(SYS_pidfd_open, pid, 0)) : -1};
  for (;;) {
    if (ready()) return WaitEnd::kReady;
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(end - Clock::now()).count();
    if (left <= 0) return WaitEnd::kTimeout;
    pollfd fds[2] = {{events.fd, POLLIN, 0}, {exited.fd, POLLIN, 0}};
    // Without inotify (a file system that has none), a tenth of a second
    // between looks is the fallback.
    const int wait = events.fd >= 0 ? static_cast<int>(left) : std::min<int>(100, static_cast<int>(left));
    const int n = poll(fds, 2, wait);
    if (n < 0 && errno != EINTR) return ready() ? WaitEnd::kReady : WaitEnd::kTimeout;
    if (n > 0 && (fds[1].revents & POLLIN)) return ready() ? WaitEnd::kReady : WaitEnd::kExited;
    if (n > 0 && (fds[0].revents & POLLIN)) {
      char buf[4096];
      while (read(events.fd, buf, sizeof(buf)) > 0) {
      }
    }
  }
}

}  // namespace alignset::e2e

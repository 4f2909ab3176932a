#pragma once

#include <atomic>
#include <mutex>
#include <string>
#include <thread>

#include "core/util/status.h"
#include "server/metrics.h"

namespace alignset::server {

// Looks for page-level damage in the cache file with PRAGMA quick_check, on
// a read-only connection of its own and a thread of its own (on a large
// file the check reads every page, which can take minutes): once at start,
// and again after the first write that fails. What it finds goes into the
// log (one error line naming the repair) and into the metric
// database_integrity_errors. Health stays SERVING: a damaged cache still
// serves every set (those on damaged pages are recomputed), and a restart
// would not repair it; `alignset cache recover` does.
class IntegrityWatch {
 public:
  IntegrityWatch(std::string db_path, Metrics* metrics);
  ~IntegrityWatch();  // waits for a check in progress

  // Starts a check unless one is running; `why` goes into the log.
  void CheckInBackground(const std::string& why);
  // The scheduler's hook: the first failed write starts a check.
  void OnWriteError(const Status& error);

 private:
  void Run(const std::string& why);

  const std::string db_path_;
  Metrics* const metrics_;
  std::atomic<bool> write_error_seen_{false};
  std::mutex mu_;
  std::thread thread_;
};

}  // namespace alignset::server

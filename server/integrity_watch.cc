#include "server/integrity_watch.h"

#include <spdlog/spdlog.h>

#include "storage/cache_recovery.h"

namespace alignset::server {

IntegrityWatch::IntegrityWatch(std::string db_path, Metrics* metrics)
    : db_path_(std::move(db_path)), metrics_(metrics) {}

IntegrityWatch::~IntegrityWatch() {
  std::lock_guard<std::mutex> lock(mu_);
  if (thread_.joinable()) thread_.join();
}

void IntegrityWatch::CheckInBackground(const std::string& why) {
  std::lock_guard<std::mutex> lock(mu_);
  if (thread_.joinable()) thread_.join();  // the previous one (rare: at most two checks)
  thread_ = std::thread([this, why] { Run(why); });
}

void IntegrityWatch::OnWriteError(const Status& error) {
  if (write_error_seen_.exchange(true)) return;
  // The damage is known already (the start-up check found it): the failed
  // write is its consequence, counted in sets_not_stored.
  if (metrics_->database_integrity_errors.load() > 0) return;
  CheckInBackground("after a failed write (" + error.message() + ")");
}

void IntegrityWatch::Run(const std::string& why) {
  auto problems = storage::QuickCheck(db_path_);
  metrics_->integrity_checks.fetch_add(1);
  if (!problems.ok()) {
    metrics_->database_integrity_errors.store(1);
    spdlog::error("database {} cannot be checked {}: {}; repair it with 'alignset cache recover "
                  "--db {} --out NEW' while the server is stopped (docs/operations.md, \"Operations\")",
                  db_path_, why, problems.status().message(), db_path_);
    return;
  }
  metrics_->database_integrity_errors.store(problems->size());
  if (problems->empty()) {
    spdlog::info("database {} passed quick_check {}", db_path_, why);
    return;
  }
  spdlog::error("database {} is damaged: quick_check {} found {} problem(s), the first: {}. Sets on "
                "damaged pages are recomputed but cannot be stored; repair it with 'alignset cache "
                "recover --db {} --out NEW' while the server is stopped (docs/operations.md, \"Operations\")",
                db_path_, why, problems->size(), problems->front(), db_path_);
}

}  // namespace alignset::server

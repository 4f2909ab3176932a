#pragma once

#include <condition_variable>
#include <cstdint>
#include <functional>
#include <map>
#include <mutex>
#include <set>
#include <string>
#include <thread>

#include "server/metrics.h"
#include "storage/set_cache.h"

namespace alignset::server {

// Keeps a writer's cache file under --max-cache-bytes.
//
// Order: least recently served first. Every hit and every stored set is a
// Touch; the order lives in memory (a write per hit would cost more than the
// hit) and is saved, whole, beside the cache file (Options::order_file: the
// names oldest first, written to a temporary file and renamed, so a crash
// leaves the previous order) every few seconds while it changes and when the
// evictor stops. At start the saved order is read back: the sets it names
// keep their places, the sets it does not name (stored by a build or a
// process that did not save them) go first, in the order they were made. A
// missing or unreadable order file is a warning, and the start falls back to
// creation times.
//
// Before a set is written, MakeRoom deletes sets (one transaction each)
// until the pages in use plus the new set fit the bound. A pinned set, one
// that a call is waiting for (Options::pinned: the scheduler's in-flight
// keys, and the set being written), is never evicted; when only pinned sets
// are left MakeRoom says so and the new set is served, not stored (nothing
// already stored is lost to make room for it). Deleted pages go to SQLite's
// free list, where the next writes reuse them; a background thread returns
// them to the file system (PRAGMA incremental_vacuum, a few hundred pages per
// short transaction), so the file shrinks too.
class CacheEvictor {
 public:
  struct Options {
    int64_t max_bytes = 0;
    // True for a set that must stay (KeyString of its key).
    std::function<bool(const std::string&)> pinned;
    // Called for each evicted set (the scheduler drops it from memory too).
    std::function<void(const std::string&)> evicted;
    // Where the order is kept between starts (empty: not kept).
    std::string order_file;
    // How often a changed order is saved.
    double save_seconds = 5.0;
  };
  CacheEvictor(storage::SetCache* cache, Metrics* metrics, Options options);
  ~CacheEvictor();  // stops the vacuum thread

  // Learns the stored sets (oldest first), switches the file to incremental
  // vacuum (once; a VACUUM of the whole file) and starts the vacuum thread.
  Status Start();

  // The set was served (or stored) now.
  void Touch(const std::string& name, const storage::SetKey& key);
  // Writes the order to Options::order_file now (also done every
  // save_seconds while it changes, and on destruction).
  Status SaveOrder();
  // Makes room for `bytes` more (a set about to be written for `key`, which
  // is pinned meanwhile). ResourceExhausted when pinned sets alone fill the
  // bound or the set is larger than the bound.
  Status MakeRoom(const storage::SetKey& key, int64_t bytes);
  // The bytes a set of n points takes in the file: its blob plus the row
  // and page overhead, rounded up to whole pages.
  int64_t EstimateBytes(uint32_t n) const;

 private:
  void VacuumLoop();
  void TouchLocked(const std::string& name, const storage::SetKey& key);

  storage::SetCache* const cache_;
  Metrics* const metrics_;
  const Options options_;
  int64_t page_size_ = 4096;

  std::mutex mu_;  // the order; MakeRoom runs under make_room_mu_ only
  uint64_t tick_ = 0;
  std::map<std::string, std::pair<uint64_t, storage::SetKey>> last_served_;
  std::set<std::pair<uint64_t, std::string>> order_;  // oldest first
  bool order_changed_ = false;
  std::mutex save_mu_;  // one SaveOrder at a time
  std::mutex make_room_mu_;

  std::mutex vacuum_mu_;
  std::condition_variable vacuum_cv_;
  bool vacuum_due_ = false;
  bool stopping_ = false;
  std::thread vacuum_thread_;
};

}  // namespace alignset::server

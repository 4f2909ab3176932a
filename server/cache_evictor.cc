#include "server/cache_evictor.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <map>
#include <vector>

#include "server/set_lru.h"

namespace alignset::server {

CacheEvictor::CacheEvictor(storage::SetCache* cache, Metrics* metrics, Options options)
    : cache_(cache), metrics_(metrics), options_(std::move(options)) {}

CacheEvictor::~CacheEvictor() {
  {
    std::lock_guard<std::mutex> lock(vacuum_mu_);
    stopping_ = true;
  }
  vacuum_cv_.notify_all();
  if (vacuum_thread_.joinable()) vacuum_thread_.join();
  if (Status s = SaveOrder(); !s.ok()) spdlog::warn("eviction order not saved: {}", s.message());
}

namespace {

// The names of a saved order, oldest first; empty when there is none.
std::vector<std::string> ReadOrder(const std::string& path) {
  std::vector<std::string> names;
  if (path.empty()) return names;
  std::ifstream in(path);
  if (!in) {
    if (std::filesystem::exists(path)) spdlog::warn("cannot read the eviction order {}: sets go by creation time", path);
    return names;
  }
  for (std::string line; std::getline(in, line);) {
    if (!line.empty()) names.push_back(line);
  }
  return names;
}

}  // namespace

Status CacheEvictor::SaveOrder() {
  if (options_.order_file.empty()) return Status::Ok();
  std::lock_guard<std::mutex> saving(save_mu_);
  std::string text;
  {
    std::lock_guard<std::mutex> lock(mu_);
    if (!order_changed_) return Status::Ok();
    order_changed_ = false;
    for (const auto& [tick, name] : order_) text += name + "\n";
  }
  const std::string tmp = options_.order_file + ".tmp";
  {
    std::ofstream out(tmp, std::ios::trunc);
    out << text;
    out.flush();
    if (!out) {
      std::lock_guard<std::mutex> lock(mu_);
      order_changed_ = true;
      return Status::Unavailable("cannot write " + tmp);
    }
  }
  std::error_code ec;
  std::filesystem::rename(tmp, options_.order_file, ec);
  if (ec) {
    std::lock_guard<std::mutex> lock(mu_);
    order_changed_ = true;
    return Status::Unavailable("cannot rename " + tmp + ": " + ec.message());
  }
  return Status::Ok();
}

Status CacheEvictor::Start() {
  if (Status s = cache_->EnableIncrementalVacuum(); !s.ok()) {
    return Status::Unavailable("--max-cache-bytes: cannot switch the cache file to incremental vacuum: " +
                               s.message());
  }
  auto space = cache_->Space();
  if (!space.ok()) return space.status();
  page_size_ = std::max<int64_t>(512, space->page_size);
  auto sets = cache_->ListSummaries();
  if (!sets.ok()) return sets.status();
  // The saved order's places; a set it does not name goes before all of
  // them, by creation time.
  std::map<std::string, size_t> saved;
  {
    const std::vector<std::string> names = ReadOrder(options_.order_file);
    for (size_t i = 0; i < names.size(); ++i) saved[names[i]] = i + 1;
  }
  std::vector<std::pair<size_t, const storage::SetSummary*>> ranked;
  for (const auto& s : *sets) {
    auto it = saved.find(KeyString(s.key));
    ranked.emplace_back(it == saved.end() ? 0 : it->second, &s);
  }
  std::stable_sort(ranked.begin(), ranked.end(), [](const auto& a, const auto& b) {
    if (a.first != b.first) return a.first < b.first;
    return a.second->created_unix < b.second->created_unix;
  });
  size_t restored = 0;
  {
    std::lock_guard<std::mutex> lock(mu_);
    for (const auto& [place, s] : ranked) {
      TouchLocked(KeyString(s->key), s->key);
      restored += place != 0;
    }
    order_changed_ = false;
  }
  if (!options_.order_file.empty()) {
    spdlog::info("eviction order: {} of {} sets from {}", restored, sets->size(), options_.order_file);
  }
  metrics_->cache_file_bytes.store(space->file_bytes());
  spdlog::info("--max-cache-bytes {}: {} sets, {} bytes in use of a {}-byte file", options_.max_bytes,
               sets->size(), space->used_bytes(), space->file_bytes());
  {
    std::lock_guard<std::mutex> lock(vacuum_mu_);
    vacuum_due_ = space->freelist_count > 0;
  }
  vacuum_thread_ = std::thread([this] { VacuumLoop(); });
  // A file already over the bound (the bound was lowered) shrinks now.
  if (Status s = MakeRoom(storage::SetKey{}, 0); !s.ok()) {
    if (s.code() != Status::Code::kResourceExhausted) return s;
    spdlog::warn("the cache file is over --max-cache-bytes: {}", s.message());
  }
  return Status::Ok();
}

void CacheEvictor::TouchLocked(const std::string& name, const storage::SetKey& key) {
  auto [it, is_new] = last_served_.try_emplace(name, 0, key);
  if (!is_new) order_.erase({it->second.first, name});
  it->second.first = ++tick_;
  order_.emplace(it->second.first, name);
  order_changed_ = true;
}

void CacheEvictor::Touch(const std::string& name, const storage::SetKey& key) {
  std::lock_guard<std::mutex> lock(mu_);
  TouchLocked(name, key);
}

int64_t CacheEvictor::EstimateBytes(uint32_t n) const {
  // 16 bytes a point, about 200 bytes of columns and index entries; the
  // blob's overflow pages each carry a 4-byte link.
  const int64_t payload = int64_t{16} * n + 200;
  const int64_t pages = (payload + page_size_ - 5) / (page_size_ - 4) + 1;
  return pages * page_size_;
}

Status CacheEvictor::MakeRoom(const storage::SetKey& key, int64_t bytes) {
  std::lock_guard<std::mutex> room(make_room_mu_);
  const std::string keep = key.n == 0 ? std::string() : KeyString(key);
  if (bytes > options_.max_bytes) {
    return Status::ResourceExhausted("a set of " + std::to_string(bytes) + " bytes is larger than --max-cache-bytes " +
                                     std::to_string(options_.max_bytes));
  }
  std::set<std::string> skipped;  // pinned, or already gone
  bool evicted_any = false;
  for (;;) {
    auto space = cache_->Space();
    if (!space.ok()) return space.status();
    metrics_->cache_file_bytes.store(space->file_bytes());
    if (space->used_bytes() + bytes <= options_.max_bytes) break;
    std::string victim;
    storage::SetKey victim_key;
    {
      std::lock_guard<std::mutex> lock(mu_);
      for (const auto& [tick, name] : order_) {
        if (name == keep || skipped.count(name) != 0) continue;
        if (options_.pinned && options_.pinned(name)) {
          skipped.insert(name);
          continue;
        }
        victim = name;
        victim_key = last_served_.at(name).second;
        break;
      }
    }
    if (victim.empty()) {
      return Status::ResourceExhausted("--max-cache-bytes " + std::to_string(options_.max_bytes) +
                                       ": every stored set is waited for; " + std::to_string(space->used_bytes()) +
                                       " bytes in use");
    }
    Status del = cache_->Delete(victim_key);
    if (!del.ok() && del.code() != Status::Code::kNotFound) return del;
    {
      std::lock_guard<std::mutex> lock(mu_);
      if (auto it = last_served_.find(victim); it != last_served_.end()) {
        order_.erase({it->second.first, victim});
        last_served_.erase(it);
        order_changed_ = true;
      }
    }
    if (del.ok()) {
      metrics_->cache_evictions.fetch_add(1, std::memory_order_relaxed);
      metrics_->cache_evicted_bytes.fetch_add(static_cast<uint64_t>(EstimateBytes(victim_key.n)),
                                              std::memory_order_relaxed);
      if (options_.evicted) options_.evicted(victim);
      spdlog::info("evicted {} (least recently served; --max-cache-bytes {})", victim, options_.max_bytes);
      evicted_any = true;
    }
  }
  if (evicted_any) {
    {
      std::lock_guard<std::mutex> lock(vacuum_mu_);
      vacuum_due_ = true;
    }
    vacuum_cv_.notify_all();
  }
  return Status::Ok();
}

void CacheEvictor::VacuumLoop() {
  for (;;) {
    {
      std::unique_lock<std::mutex> lock(vacuum_mu_);
      // Wakes to save a changed order too.
      const bool due = vacuum_cv_.wait_for(lock, std::chrono::duration<double>(options_.save_seconds),
                                           [&] { return stopping_ || vacuum_due_; });
      if (stopping_) return;
      if (!due) {
        lock.unlock();
        if (Status s = SaveOrder(); !s.ok()) spdlog::warn("eviction order not saved: {}", s.message());
        continue;
      }
      vacuum_due_ = false;
    }
    // A few hundred pages per transaction: the cache's connection is held
    // only briefly, so hits go on between the steps.
    for (;;) {
      auto left = cache_->IncrementalVacuum(256);
      if (!left.ok()) {
        spdlog::warn("incremental vacuum: {}", left.status().message());
        break;
      }
      if (*left == 0) break;
      std::lock_guard<std::mutex> lock(vacuum_mu_);
      if (stopping_) return;
    }
    metrics_->cache_vacuums.fetch_add(1, std::memory_order_relaxed);
    if (auto space = cache_->Space(); space.ok()) metrics_->cache_file_bytes.store(space->file_bytes());
  }
}

}  // namespace alignset::server

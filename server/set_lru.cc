#include "server/set_lru.h"

namespace alignset::server {

std::string KeyString(const storage::SetKey& key) { return storage::KeyToString(key); }

std::shared_ptr<const CanonicalEntry> SetLru::Get(const std::string& key) {
  std::lock_guard<std::mutex> lock(mu_);
  auto it = index_.find(key);
  if (it == index_.end()) return nullptr;
  order_.splice(order_.begin(), order_, it->second);
  return it->second->second;
}

void SetLru::Put(const std::string& key, std::shared_ptr<const CanonicalEntry> entry) {
  const size_t charge = entry->ChargedBytes();
  std::lock_guard<std::mutex> lock(mu_);
  if (auto it = index_.find(key); it != index_.end()) {
    bytes_ -= it->second->second->ChargedBytes();
    order_.erase(it->second);
    index_.erase(it);
  }
  if (charge > capacity_) return;  // would evict everything for one set
  order_.emplace_front(key, std::move(entry));
  index_[key] = order_.begin();
  bytes_ += charge;
  while (bytes_ > capacity_ && !order_.empty()) {
    bytes_ -= order_.back().second->ChargedBytes();
    index_.erase(order_.back().first);
    order_.pop_back();
  }
}

void SetLru::Erase(const std::string& key) {
  std::lock_guard<std::mutex> lock(mu_);
  auto it = index_.find(key);
  if (it == index_.end()) return;
  bytes_ -= it->second->second->ChargedBytes();
  order_.erase(it->second);
  index_.erase(it);
}

size_t SetLru::bytes() const {
  std::lock_guard<std::mutex> lock(mu_);
  return bytes_;
}

size_t SetLru::size() const {
  std::lock_guard<std::mutex> lock(mu_);
  return index_.size();
}

}  // namespace alignset::server

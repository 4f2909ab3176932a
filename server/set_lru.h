#pragma once

#include <cstddef>
#include <list>
#include <memory>
#include <mutex>
#include <string>
#include <unordered_map>

#include "server/canonical_entry.h"

namespace alignset::server {

// The string a SetKey is indexed by in memory and named by in logs.
std::string KeyString(const storage::SetKey& key);

// Least-recently-used canonical sets, bounded by their charged bytes, so that
// a hit does not go to SQLite (and decode and verify a blob) every time.
// Entries are shared: eviction never invalidates a response being built.
class SetLru {
 public:
  explicit SetLru(size_t capacity_bytes) : capacity_(capacity_bytes) {}

  std::shared_ptr<const CanonicalEntry> Get(const std::string& key);
  void Put(const std::string& key, std::shared_ptr<const CanonicalEntry> entry);
  void Erase(const std::string& key);
  size_t bytes() const;
  size_t capacity() const { return capacity_; }
  size_t size() const;

 private:
  using Item = std::pair<std::string, std::shared_ptr<const CanonicalEntry>>;
  size_t capacity_;
  mutable std::mutex mu_;
  std::list<Item> order_;  // front: most recent
  std::unordered_map<std::string, std::list<Item>::iterator> index_;
  size_t bytes_ = 0;
};

}  // namespace alignset::server

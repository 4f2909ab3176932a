#include "core/optimize/lattice_term_cache.h"

#include <utility>

namespace alignset {
namespace {
// An unordered_map node (key, value, next pointer, hash) plus its bucket.
constexpr size_t kSparseBytesPerTerm = 48;
constexpr size_t kEntryOverheadBytes = 128;
}  // namespace

LatticeTermCache::LatticeTermCache(size_t max_bytes) : max_bytes_(max_bytes) {}

size_t LatticeTermCache::BytesOf(const Entry& e) {
  return kEntryOverheadBytes + (e.dense ? e.dense->size() * sizeof(Terms) : 0) +
         e.sparse.size() * kSparseBytesPerTerm + e.object_bytes;
}

void LatticeTermCache::TouchLocked(Entry* e) { lru_.splice(lru_.begin(), lru_, e->age); }

void LatticeTermCache::EvictLocked(const Entry* keep) {
  // Objects first (they are rebuilt in milliseconds and weigh megabytes),
  // then terms (each one is a generator's pass over its dual points).
  for (bool objects : {true, false}) {
    auto it = lru_.end();
    while (bytes_ > max_bytes_ && it != lru_.begin()) {
      --it;
      auto found = entries_.find(*it);
      if (&found->second == keep || (objects && !found->second.object)) continue;
      bytes_ -= found->second.bytes;
      entries_.erase(found);
      it = lru_.erase(it);
    }
  }
}

std::shared_ptr<const std::vector<LatticeTermCache::Terms>> LatticeTermCache::FindDense(const Key& key) {
  std::lock_guard<std::mutex> lock(mu_);
  auto it = entries_.find(key);
  if (it == entries_.end() || !it->second.dense) {
    ++misses_;
    return nullptr;
  }
  TouchLocked(&it->second);
  hits_ += it->second.dense->size();
  return it->second.dense;
}

template <class Fill>
void LatticeTermCache::PutLocked(const Key& key, const Fill& fill) {
  auto [it, inserted] = entries_.try_emplace(key);
  Entry& e = it->second;
  if (inserted) {
    lru_.push_front(key);
    e.age = lru_.begin();
  } else {
    TouchLocked(&e);
  }
  if (!fill(e)) return;
  bytes_ -= e.bytes;
  e.bytes = BytesOf(e);
  bytes_ += e.bytes;
  // An entry past the bound on its own is dropped rather than kept.
  if (e.bytes > max_bytes_) {
    bytes_ -= e.bytes;
    lru_.erase(e.age);
    entries_.erase(it);
    return;
  }
  EvictLocked(&e);
}

void LatticeTermCache::PutDense(const Key& key, std::shared_ptr<const std::vector<Terms>> terms) {
  std::lock_guard<std::mutex> lock(mu_);
  PutLocked(key, [&](Entry& e) {
    if (e.dense) return false;  // another search stored the same values first
    e.dense = std::move(terms);
    return true;
  });
}

void LatticeTermCache::FindSparse(const Key& key, const std::vector<uint32_t>& gs,
                                  std::vector<Terms>* values, std::vector<bool>* found) {
  values->assign(gs.size(), Terms{});
  found->assign(gs.size(), false);
  std::lock_guard<std::mutex> lock(mu_);
  auto it = entries_.find(key);
  if (it == entries_.end()) {
    misses_ += gs.size();
    return;
  }
  TouchLocked(&it->second);
  for (size_t i = 0; i < gs.size(); ++i) {
    auto v = it->second.sparse.find(gs[i]);
    if (v == it->second.sparse.end()) {
      ++misses_;
      continue;
    }
    (*values)[i] = v->second;
    (*found)[i] = true;
    ++hits_;
  }
}

void LatticeTermCache::PutSparse(const Key& key, const std::vector<uint32_t>& gs,
                                 const std::vector<Terms>& values) {
  std::lock_guard<std::mutex> lock(mu_);
  PutLocked(key, [&](Entry& e) {
    for (size_t i = 0; i < gs.size(); ++i) e.sparse.emplace(gs[i], values[i]);
    return true;
  });
}

std::shared_ptr<const void> LatticeTermCache::FindObject(const Key& key) {
  std::lock_guard<std::mutex> lock(mu_);
  auto it = entries_.find(key);
  if (it == entries_.end() || !it->second.object) return nullptr;
  TouchLocked(&it->second);
  return it->second.object;
}

void LatticeTermCache::PutObject(const Key& key, std::shared_ptr<const void> object, size_t bytes) {
  std::lock_guard<std::mutex> lock(mu_);
  PutLocked(key, [&](Entry& e) {
    if (e.object) return false;
    e.object = std::move(object);
    e.object_bytes = bytes;
    return true;
  });
}

LatticeTermCache::Stats LatticeTermCache::stats() const {
  std::lock_guard<std::mutex> lock(mu_);
  return {hits_, misses_, bytes_, entries_.size()};
}

}  // namespace alignset

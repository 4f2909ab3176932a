#pragma once

#include <cstddef>
#include <cstdint>
#include <list>
#include <map>
#include <memory>
#include <mutex>
#include <tuple>
#include <unordered_map>
#include <vector>

namespace alignset {

// The aligned-lattice search's per-direction work, kept between searches
// (AlignedLatticeOptions::cache). A key's score is a sum of terms that each
// belong to one of its directions (or to N alone: the corner term), so a
// server asked for the 4141 pairs of a space one key at a time scores each
// (direction, generator) once, as a batch of all of them would: at N = 4096
// the pairs take 27 s in one batch on two cores, 9 minutes through the
// server one by one without this and 67 s with it (bench/lattice_fill.sh).
// The values are the very doubles a fresh search computes, so a choice
// never depends on what was searched before it, on the order, or on what
// was evicted; tests/core/optimize checks it.
//
// Entries are per (N, window, direction, stage); the least recently used go
// first once `max_bytes` is passed. Thread-safe: two searches that miss the
// same entry both compute it and the second store is a no-op.
class LatticeTermCache {
 public:
  // kSequence: a lattice sequence's whole choice (core/optimize/lattice_sequence.h),
  // an object under n = 0: one search serves the key at every N.
  enum class Stage : uint8_t { kCoarse = 0, kFull = 1, kFullFamily = 2, kSequence = 3 };
  struct Key {
    uint32_t n = 0;
    Stage stage = Stage::kCoarse;
    double window_deg = 0.0;
    double direction_deg = 0.0;
    bool folded = false;  // AlignedLatticeOptions::folded
    bool operator<(const Key& o) const {
      return std::tie(n, stage, window_deg, direction_deg, folded) <
             std::tie(o.n, o.stage, o.window_deg, o.direction_deg, o.folded);
    }
  };
  struct Stats {
    uint64_t hits = 0;    // terms found
    uint64_t misses = 0;  // terms computed
    size_t bytes = 0;
    size_t entries = 0;
  };

  explicit LatticeTermCache(size_t max_bytes = size_t{128} << 20);
  LatticeTermCache(const LatticeTermCache&) = delete;
  LatticeTermCache& operator=(const LatticeTermCache&) = delete;

  // A generator's terms in one direction's pass: its edges' and the corner
  // term's (the same in every direction; kept with each so that a held
  // direction never lacks it).
  struct Terms {
    double edges = 0.0;
    double corner = 0.0;
  };

  // A coarse stage's terms, one per candidate generator in the search's
  // order; null when not held.
  std::shared_ptr<const std::vector<Terms>> FindDense(const Key& key);
  void PutDense(const Key& key, std::shared_ptr<const std::vector<Terms>> terms);
  // The final stage's terms of single generators: values[i] for gs[i] where
  // held (found[i] true).
  void FindSparse(const Key& key, const std::vector<uint32_t>& gs, std::vector<Terms>* values,
                  std::vector<bool>* found);
  void PutSparse(const Key& key, const std::vector<uint32_t>& gs, const std::vector<Terms>& values);

  // Whatever the search keeps to compute more terms of a direction (its
  // edges' coefficient tables: 3.5 MB a direction at N = 4096, rebuilt for
  // every key that misses one final term otherwise), counted as `bytes`.
  std::shared_ptr<const void> FindObject(const Key& key);
  void PutObject(const Key& key, std::shared_ptr<const void> object, size_t bytes);

  Stats stats() const;
  size_t max_bytes() const { return max_bytes_; }

 private:
  struct Entry {
    std::shared_ptr<const std::vector<Terms>> dense;
    std::unordered_map<uint32_t, Terms> sparse;
    std::shared_ptr<const void> object;
    size_t object_bytes = 0;
    size_t bytes = 0;
    std::list<Key>::iterator age;
  };
  static size_t BytesOf(const Entry& e);
  // mu_ held: marks the entry used now.
  void TouchLocked(Entry* e);
  // mu_ held: lets `fill` add to the key's entry (made if missing; fill
  // returns false when the entry holds that already), then keeps the bound.
  template <class Fill>
  void PutLocked(const Key& key, const Fill& fill);
  // mu_ held: drops the least recently used entries but `keep` until the
  // total is within max_bytes_.
  void EvictLocked(const Entry* keep);

  const size_t max_bytes_;
  mutable std::mutex mu_;
  std::map<Key, Entry> entries_;
  std::list<Key> lru_;  // front: most recently used
  size_t bytes_ = 0;
  uint64_t hits_ = 0, misses_ = 0;
};

}  // namespace alignset

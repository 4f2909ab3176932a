#pragma once

#include <array>
#include <memory>
#include <mutex>
#include <optional>
#include <string>

#include "core/align/canonical.h"
#include "storage/set_cache.h"

namespace alignset::server {

// Packs points as the wire wants them: little-endian float64, x0 y0 x1 y1 ...
std::string EncodePoints(const PointSet& points);

// A canonical set as the server holds it in memory: the stored record plus,
// per group element, its aligned points already encoded for the wire. A cache
// hit then costs a map lookup and one copy into the response, not an
// alignment and an encoding per request. Immutable apart from that lazily
// filled table, which is guarded.
class CanonicalEntry {
 public:
  // `stored`: the record is in SQLite (false: optimized and served, but the
  // write failed; responses say so).
  explicit CanonicalEntry(storage::SetRecord record, bool stored = true)
      : record_(std::move(record)), stored_(stored) {}

  const storage::SetRecord& record() const { return record_; }
  bool stored() const { return stored_; }
  // The set aligned by `ops`, encoded; built once per element.
  std::shared_ptr<const std::string> Encoded(const AlignOps& ops) const;
  // For a lattice's record (realization `seed`, tent-folded or not): the
  // canonical set's generator, read back from the points on first use
  // (LatticeGeneratorOf, O(N)) since the cache stores points only; nullopt
  // when the points are no such lattice.
  std::optional<uint32_t> LatticeGenerator(uint64_t seed, bool folded) const;
  // What the entry may grow to: the points plus the four alignments a
  // canonicalization can ask for.
  size_t ChargedBytes() const { return record_.points.size() * sizeof(Point2) * 5 + 256; }

 private:
  storage::SetRecord record_;
  const bool stored_;
  mutable std::mutex mu_;
  mutable std::array<std::shared_ptr<const std::string>, 8> encoded_;
  mutable bool generator_read_ = false;
  mutable std::optional<uint32_t> generator_;
};

}  // namespace alignset::server

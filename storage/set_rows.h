#pragma once

// How a cached set maps onto a row of the `sets` table: shared by the cache
// itself (sqlite_set_cache.cc) and the damage scan (cache_recovery.cc).
#include "storage/set_cache.h"
#include "storage/sqlite_handle.h"

namespace alignset::storage {

// Column order of every full-row query; the blob is last (see schema.cc).
inline constexpr const char* kColumns =
    "n, dir_count, phi1, phi2, profile, loss_total, loss_spectrum, loss_sw, iterations, "
    "optimize_seconds, engine, created_unix, algorithm_version, checksum, points";
inline constexpr int kChecksumCol = 13;
inline constexpr int kPointsCol = 14;

// Binds the key to parameters ?1..?5.
void BindKey(Stmt& s, const SetKey& key);
// Columns 0..4 of kColumns.
SetKey KeyFromRow(const Stmt& s);
// Columns 5..12 of kColumns.
template <typename T>
void MetadataFromRow(const Stmt& s, T* out) {
  out->loss.total = s.Double(5);
  out->loss.spectrum = s.Double(6);
  out->loss.sw = s.Double(7);
  out->iterations = static_cast<int>(s.Int(8));
  out->optimize_seconds = s.Double(9);
  out->engine = s.Text(10);
  out->created_unix = s.Int(11);
  out->algorithm_version = static_cast<int>(s.Int(12));
}
// A whole row (kColumns), checked: a key that fails validation, a checksum
// mismatch or a malformed blob is DataLoss naming the key.
StatusOr<SetRecord> RecordFromRow(const Stmt& s);

}  // namespace alignset::storage

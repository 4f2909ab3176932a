#pragma once

// How a cached set maps onto a row of the `sets` table: shared by the cache
// itself (sqlite_set_cache.cc) and the damage scan (cache_recovery.cc).
#include "storage/set_cache.h"
#include "storage/sqlite_handle.h"

namespace alignset::storage {

// Column order of every full-row query; the blob is last (see schema.cc).
inline constexpr const char* kColumns =
    "n, dir_count, phi1, phi2, realization, profile, loss_total, loss_spectrum, loss_sw, "
    "iterations, optimize_seconds, engine, created_unix, algorithm_version, checksum, points";
// The same for a file from before schema version 3, whose sets are all
// realization 0.
inline constexpr const char* kColumnsBeforeRealizations =
    "n, dir_count, phi1, phi2, 0, profile, loss_total, loss_spectrum, loss_sw, "
    "iterations, optimize_seconds, engine, created_unix, algorithm_version, checksum, points";
// The key columns alone (0..5 of kColumns), for either schema.
inline constexpr const char* kKeyColumns = "n, dir_count, phi1, phi2, realization, profile";
inline constexpr const char* kKeyColumnsBeforeRealizations = "n, dir_count, phi1, phi2, 0, profile";
inline constexpr int kChecksumCol = 14;
inline constexpr int kPointsCol = 15;
// The first schema version whose rows have a realization column.
inline constexpr int kFirstSchemaWithRealizations = 3;

// Binds the key to parameters ?1..?6.
void BindKey(Stmt& s, const SetKey& key);
// Columns 0..5 of kColumns.
SetKey KeyFromRow(const Stmt& s);
// Columns 6..13 of kColumns.
template <typename T>
void MetadataFromRow(const Stmt& s, T* out) {
  out->loss.total = s.Double(6);
  out->loss.spectrum = s.Double(7);
  out->loss.sw = s.Double(8);
  out->iterations = static_cast<int>(s.Int(9));
  out->optimize_seconds = s.Double(10);
  out->engine = s.Text(11);
  out->created_unix = s.Int(12);
  out->algorithm_version = static_cast<int>(s.Int(13));
}
// A whole row (kColumns), checked: a key that fails validation, a checksum
// mismatch or a malformed blob is DataLoss naming the key.
StatusOr<SetRecord> RecordFromRow(const Stmt& s);

}  // namespace alignset::storage

#include "storage/set_rows.h"

#include <cmath>

#include "storage/blob_codec.h"

namespace alignset::storage {

// The phi1 column holds the key's first angle in degrees. A whole-degree key
// is bound as an INTEGER, exactly as before the quarter-degree grid, so the
// rows of existing caches keep their keys; a quarter-degree key (30.25) is
// bound as a REAL, which the column's INTEGER affinity stores as REAL since
// it has no integer value. SQLite compares INTEGER and REAL numerically, so
// one primary key and one ORDER BY cover both, and no migration is needed.
void BindKey(Stmt& s, const SetKey& key) {
  s.BindInt(1, key.n);
  s.BindInt(2, key.dirs.count);
  if (key.dirs.phi1_quarter == 0) {
    s.BindInt(3, key.dirs.phi1);
  } else {
    s.BindDouble(3, Phi1Degrees(key.dirs));
  }
  s.BindInt(4, key.dirs.phi2);
  s.BindInt(5, key.realization);
  s.BindText(6, key.profile);
}

SetKey KeyFromRow(const Stmt& s) {
  SetKey k;
  const int64_t n = s.Int(0);
  k.n = (n < 0 || n > UINT32_MAX) ? 0 : static_cast<uint32_t>(n);
  k.dirs.count = static_cast<int>(s.Int(1));
  // Whole degrees and quarters are exact in a double; anything else (not
  // written by alignset) keeps a quarter of -1, which ValidateKey refuses.
  const double phi1 = s.Double(2);
  const double whole = std::floor(phi1);
  const double quarters = (phi1 - whole) * 4.0;
  k.dirs.phi1 = static_cast<int>(whole);
  k.dirs.phi1_quarter = quarters == std::floor(quarters) ? static_cast<int>(quarters) : -1;
  k.dirs.phi2 = static_cast<int>(s.Int(3));
  const int64_t r = s.Int(4);
  k.realization = (r < 0 || r > UINT32_MAX) ? UINT32_MAX : static_cast<uint32_t>(r);
  k.profile = s.Text(5);
  return k;
}

StatusOr<SetRecord> RecordFromRow(const Stmt& s) {
  SetRecord r;
  r.key = KeyFromRow(s);
  Status valid = ValidateKey(r.key);
  if (!valid.ok()) return Status::DataLoss("stored row has an invalid key: " + valid.message());
  MetadataFromRow(s, &r);
  const int64_t crc = s.Int(kChecksumCol);
  if (crc < 0 || crc > UINT32_MAX) return Status::DataLoss(KeyToString(r.key) + ": bad checksum value");
  auto points = VerifyAndUnpack(s.Blob(kPointsCol), static_cast<uint32_t>(crc), r.key.n);
  if (!points.ok()) return Status::DataLoss(KeyToString(r.key) + ": " + points.status().message());
  r.points = std::move(points).value();
  return r;
}

}  // namespace alignset::storage

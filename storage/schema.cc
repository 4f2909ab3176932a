#include "storage/schema.h"

#include <ctime>

namespace alignset::storage {

const std::vector<Migration>& Migrations() {
  // The point blob is the last column: SQLite stores a large value in
  // overflow pages, and a column after it could only be read by walking the
  // whole overflow chain. Listing metadata then reads no blob.
  static const std::vector<Migration> kMigrations = {
      {1, "canonical sets keyed by n, directions and profile",
       R"sql(
CREATE TABLE sets (
  n                 INTEGER NOT NULL CHECK (n > 0),
  dir_count         INTEGER NOT NULL CHECK (dir_count IN (1, 2)),
  phi1              INTEGER NOT NULL,
  phi2              INTEGER NOT NULL,
  profile           TEXT    NOT NULL,
  loss_total        REAL    NOT NULL,
  loss_spectrum     REAL    NOT NULL,
  loss_sw           REAL    NOT NULL,
  iterations        INTEGER NOT NULL,
  optimize_seconds  REAL    NOT NULL,
  engine            TEXT    NOT NULL,
  created_unix      INTEGER NOT NULL,
  algorithm_version INTEGER NOT NULL,
  checksum          INTEGER NOT NULL,
  points            BLOB    NOT NULL,
  PRIMARY KEY (n, dir_count, phi1, phi2, profile)
);
)sql"},
      {2, "index for listing one profile",
       "CREATE INDEX sets_by_profile ON sets (profile, n, dir_count, phi1, phi2);"},
      // SQLite cannot change a primary key in place: the table is rebuilt,
      // every existing row becoming realization 0 (the set it always was).
      {3, "realization index in the key; existing sets are realization 0",
       R"sql(
CREATE TABLE sets_v3 (
  n                 INTEGER NOT NULL CHECK (n > 0),
  dir_count         INTEGER NOT NULL CHECK (dir_count IN (1, 2)),
  phi1              INTEGER NOT NULL,
  phi2              INTEGER NOT NULL,
  realization       INTEGER NOT NULL DEFAULT 0 CHECK (realization >= 0),
  profile           TEXT    NOT NULL,
  loss_total        REAL    NOT NULL,
  loss_spectrum     REAL    NOT NULL,
  loss_sw           REAL    NOT NULL,
  iterations        INTEGER NOT NULL,
  optimize_seconds  REAL    NOT NULL,
  engine            TEXT    NOT NULL,
  created_unix      INTEGER NOT NULL,
  algorithm_version INTEGER NOT NULL,
  checksum          INTEGER NOT NULL,
  points            BLOB    NOT NULL,
  PRIMARY KEY (n, dir_count, phi1, phi2, realization, profile)
);
INSERT INTO sets_v3 (n, dir_count, phi1, phi2, realization, profile, loss_total, loss_spectrum,
                     loss_sw, iterations, optimize_seconds, engine, created_unix,
                     algorithm_version, checksum, points)
  SELECT n, dir_count, phi1, phi2, 0, profile, loss_total, loss_spectrum, loss_sw, iterations,
         optimize_seconds, engine, created_unix, algorithm_version, checksum, points FROM sets;
DROP TABLE sets;
ALTER TABLE sets_v3 RENAME TO sets;
CREATE INDEX sets_by_profile ON sets (profile, n, dir_count, phi1, phi2, realization);
)sql"},
  };
  return kMigrations;
}

int LatestSchemaVersion() { return Migrations().back().version; }

StatusOr<int> SchemaVersion(const Db& db) {
  auto exists = Stmt::Prepare(
      db.get(), "SELECT 1 FROM sqlite_master WHERE type = 'table' AND name = 'schema_version'");
  if (!exists.ok()) return exists.status();
  auto row = exists->Step();
  if (!row.ok()) return row.status();
  if (!*row) return 0;
  auto max = Stmt::Prepare(db.get(), "SELECT COALESCE(MAX(version), 0) FROM schema_version");
  if (!max.ok()) return max.status();
  row = max->Step();
  if (!row.ok()) return row.status();
  return static_cast<int>(max->Int(0));
}

Status Migrate(const Db& db, const std::vector<Migration>& steps) {
  const int target = steps.empty() ? 0 : steps.back().version;
  for (size_t i = 0; i < steps.size(); ++i) {
    if (steps[i].version != static_cast<int>(i) + 1) {
      return Status::Internal("migration steps must be numbered 1, 2, ... in order");
    }
  }
  auto newer = [&](int v) {
    return Status::InvalidArgument("database schema version " + std::to_string(v) +
                                   " is newer than this build understands (" +
                                   std::to_string(target) + ")");
  };
  // The common case, an up-to-date file, takes no write lock.
  auto before = SchemaVersion(db);
  if (!before.ok()) return before.status();
  if (*before > target) return newer(*before);
  if (*before == target) return Status::Ok();
  for (const Migration& step : steps) {
    auto tx = Transaction::Begin(db, Transaction::Kind::kWrite);
    if (!tx.ok()) return tx.status();
    Status s = db.Exec(
        "CREATE TABLE IF NOT EXISTS schema_version ("
        " version INTEGER PRIMARY KEY, applied_unix INTEGER NOT NULL, description TEXT NOT NULL)");
    if (!s.ok()) return s;
    auto current = SchemaVersion(db);
    if (!current.ok()) return current.status();
    if (*current > target) return newer(*current);
    if (*current >= step.version) continue;  // rolls back the no-op transaction
    s = db.Exec(step.sql);
    if (!s.ok()) return Status::Internal("migration " + std::to_string(step.version) + ": " + s.message());
    auto ins = Stmt::Prepare(db.get(),
                             "INSERT INTO schema_version (version, applied_unix, description) "
                             "VALUES (?1, ?2, ?3)");
    if (!ins.ok()) return ins.status();
    ins->BindInt(1, step.version);
    ins->BindInt(2, static_cast<int64_t>(std::time(nullptr)));
    ins->BindText(3, step.description);
    s = ins->Run();
    if (!s.ok()) return s;
    s = tx->Commit();
    if (!s.ok()) return s;
  }
  return Status::Ok();
}

}  // namespace alignset::storage

#pragma once

#include <string>
#include <vector>

#include "core/util/status.h"
#include "storage/sqlite_handle.h"

namespace alignset::storage {

// One step of the schema history. Steps are applied in order, each in its
// own transaction together with its row in `schema_version`, so a crash
// leaves the file at a whole version, never between two.
struct Migration {
  int version;           // 1, 2, ... without gaps
  std::string description;
  std::string sql;       // one or more statements
};

// The schema's history, oldest first. Never edit a released step; append one.
const std::vector<Migration>& Migrations();
int LatestSchemaVersion();

// The highest applied version; 0 for an empty file or one without the
// version table.
StatusOr<int> SchemaVersion(const Db& db);

// Brings the file up to the last of `steps` (Migrations() in production;
// tests pass a prefix to make an older file). Safe against another process
// migrating at the same time: the version is re-read under the write lock.
// A file newer than the last step is refused rather than misread.
Status Migrate(const Db& db, const std::vector<Migration>& steps);

}  // namespace alignset::storage

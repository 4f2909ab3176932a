#include "storage/cache_recovery.h"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <limits>
#include <map>
#include <optional>
#include <set>
#include <tuple>

#include "storage/partial_file.h"
#include "storage/schema.h"
#include "storage/set_rows.h"
#include "storage/sqlite_handle.h"

namespace alignset::storage {
namespace {

constexpr int kBusyTimeoutMs = 5000;
constexpr size_t kMaxProblems = 100;

StatusOr<Db> OpenReader(const std::string& path) {
  if (!std::filesystem::exists(path)) return Status::NotFound(path + " does not exist");
  return Db::Open(path, SQLITE_OPEN_READONLY | SQLITE_OPEN_NOMUTEX, kBusyTimeoutMs);
}

void Note(std::vector<std::string>* problems, const std::string& line) {
  if (problems->size() < kMaxProblems) problems->push_back(line);
}

bool KeyLess(const SetKey& a, const SetKey& b) {
  return std::tie(a.n, a.dirs.count, a.dirs.phi1, a.dirs.phi2, a.realization, a.profile) <
         std::tie(b.n, b.dirs.count, b.dirs.phi1, b.dirs.phi2, b.realization, b.profile);
}

// The first row at or after `rowid` in the table: its rowid, nullopt at the
// end of the table, or an error when the seek lands on a damaged page.
StatusOr<std::optional<int64_t>> Probe(const Db& db, int64_t rowid) {
  auto stmt = Stmt::Prepare(db.get(), "SELECT rowid FROM sets NOT INDEXED WHERE rowid >= ?1 ORDER BY rowid LIMIT 1");
  if (!stmt.ok()) return stmt.status();
  stmt->BindInt(1, rowid);
  auto row = stmt->Step();
  if (!row.ok()) return row.status();
  if (!*row) return std::optional<int64_t>();
  return std::optional<int64_t>(stmt->Int(0));
}

// After a damaged page following `last`: the smallest probe value past the
// damage whose seek succeeds (doubling steps, then bisection: a seek fails
// exactly while it lands in the damaged range). nullopt when nothing past
// `last` can be reached.
std::optional<int64_t> SkipDamage(const Db& db, int64_t last) {
  constexpr int64_t kMax = std::numeric_limits<int64_t>::max();
  int64_t bad = last, good = 0;
  bool found = false;
  for (int64_t step = 1;; step = step > kMax / 2 ? kMax : step * 2) {
    const int64_t p = last > kMax - step ? kMax : last + step;
    if (Probe(db, p).ok()) {
      good = p;
      found = true;
      break;
    }
    bad = p;
    if (p == kMax) break;
  }
  if (!found) return std::nullopt;
  while (good - bad > 1) {
    const int64_t mid = bad + (good - bad) / 2;
    (Probe(db, mid).ok() ? good : bad) = mid;
  }
  return good;
}

}  // namespace

StatusOr<std::vector<std::string>> QuickCheck(const std::string& path, int max_problems) {
  auto db = OpenReader(path);
  if (!db.ok()) return db.status();
  auto stmt = Stmt::Prepare(db->get(), "PRAGMA quick_check(" + std::to_string(std::max(1, max_problems)) + ")");
  if (!stmt.ok()) return Status::DataLoss(path + " cannot be checked: " + stmt.status().message());
  std::vector<std::string> problems;
  for (;;) {
    auto row = stmt->Step();
    if (!row.ok()) {  // the check itself ran into the damage
      problems.push_back("quick_check stopped: " + row.status().message());
      break;
    }
    if (!*row) break;
    std::string line = stmt->Text(0);
    // SQLite's lines may span several ("*** in database main ***\nPage 14:
    // ..."): one line each, for logs.
    for (char& c : line) {
      if (c == '\n' || c == '\r') c = ' ';
    }
    if (line != "ok") problems.push_back(line);
  }
  return problems;
}

StatusOr<DamageScan> ScanForDamage(const std::string& path,
                                   const std::function<void(SetRecord&&)>& on_readable) {
  auto db = OpenReader(path);
  if (!db.ok()) return db.status();
  auto version = SchemaVersion(*db);
  if (!version.ok()) return Status::DataLoss("the schema of " + path + " cannot be read: " + version.status().message());
  if (*version < 1) return Status::InvalidArgument(path + " holds no alignset cache");
  // Files from before schema version 3 have no realization column: their
  // sets are all realization 0 (as MergeFrom reads them).
  const bool before_realizations = *version < kFirstSchemaWithRealizations;
  const std::string key_columns = before_realizations ? kKeyColumnsBeforeRealizations : kKeyColumns;
  const char* all_columns = before_realizations ? kColumnsBeforeRealizations : kColumns;
  auto tx = Transaction::Begin(*db, Transaction::Kind::kRead);  // one consistent snapshot
  if (!tx.ok()) return tx.status();

  DamageScan scan;
  std::map<int64_t, SetKey> by_rowid;           // every row any source names
  std::map<int64_t, bool> named_by_index;       // rowid -> an index names it

  // 1. The indexes: covering scans that never touch the table's pages.
  std::vector<std::string> indexes;
  {
    auto stmt = Stmt::Prepare(db->get(), "SELECT name FROM sqlite_master WHERE type = 'index' AND tbl_name = 'sets'");
    if (!stmt.ok()) return Status::DataLoss("the schema of " + path + " cannot be read: " + stmt.status().message());
    for (;;) {
      auto row = stmt->Step();
      if (!row.ok()) return Status::DataLoss("the schema of " + path + " cannot be read: " + row.status().message());
      if (!*row) break;
      indexes.push_back(stmt->Text(0));
    }
  }
  for (const std::string& index : indexes) {
    auto stmt = Stmt::Prepare(db->get(), "SELECT " + key_columns + ", rowid FROM sets INDEXED BY \"" +
                                             index + "\"");
    if (!stmt.ok()) {
      Note(&scan.problems, "index " + index + ": " + stmt.status().message());
      continue;
    }
    for (;;) {
      auto row = stmt->Step();
      if (!row.ok()) {
        Note(&scan.problems, "index " + index + ": " + row.status().message());
        break;
      }
      if (!*row) break;
      const int64_t rowid = stmt->Int(6);
      by_rowid.emplace(rowid, KeyFromRow(*stmt));
      named_by_index[rowid] = true;
    }
  }

  // 2. The table in rowid order, skipping damaged pages. Seeks use
  // "rowid >= start": a seek for "> r" lands on the page that holds r.
  int64_t start = 1;  // rowids start at 1
  for (;;) {
    auto stmt = Stmt::Prepare(db->get(), "SELECT " + key_columns + ", rowid FROM sets NOT INDEXED "
                                         "WHERE rowid >= ?1 ORDER BY rowid");
    if (!stmt.ok()) return Status::DataLoss("the table of " + path + " cannot be read: " + stmt.status().message());
    stmt->BindInt(1, start);
    int64_t last = start - 1;
    bool damaged = false;
    for (;;) {
      auto row = stmt->Step();
      if (!row.ok()) {
        Note(&scan.problems, "table after rowid " + std::to_string(last) + ": " + row.status().message());
        damaged = true;
        break;
      }
      if (!*row) break;
      last = stmt->Int(6);
      by_rowid.emplace(last, KeyFromRow(*stmt));
    }
    if (!damaged) break;
    ++scan.unreachable_ranges;
    const std::optional<int64_t> next = SkipDamage(*db, last);
    if (!next || *next <= start) break;  // nothing past it, or no progress
    start = *next;
  }

  // 3. Every row by its rowid, whole and checked.
  std::set<std::string> readable_keys;
  std::map<std::string, SetKey> damaged;
  for (const auto& [rowid, key] : by_rowid) {
    auto stmt = Stmt::Prepare(db->get(), std::string("SELECT ") + all_columns + " FROM sets NOT INDEXED WHERE rowid = ?1");
    if (!stmt.ok()) return stmt.status();
    stmt->BindInt(1, rowid);
    auto row = stmt->Step();
    if (!row.ok()) {
      Note(&scan.problems, KeyToString(key) + ": " + row.status().message());
      damaged.emplace(KeyToString(key), key);
      continue;
    }
    if (!*row) {  // an index names a row the table no longer has
      Note(&scan.problems, KeyToString(key) + ": named by an index, missing from the table");
      damaged.emplace(KeyToString(key), key);
      continue;
    }
    auto rec = RecordFromRow(*stmt);
    if (!rec.ok() || (named_by_index.count(rowid) && !(rec->key == key))) {
      Note(&scan.problems, rec.ok() ? KeyToString(key) + ": the index and the table disagree on the key"
                                    : rec.status().message());
      damaged.emplace(KeyToString(key), key);
      continue;
    }
    readable_keys.insert(KeyToString(rec->key));
    ++scan.readable;
    if (on_readable) on_readable(std::move(rec).value());
  }
  for (const auto& [name, key] : damaged) {
    if (!readable_keys.count(name)) scan.damaged.push_back(key);
  }
  std::sort(scan.damaged.begin(), scan.damaged.end(), KeyLess);
  return scan;
}

StatusOr<RecoverReport> RecoverCache(const std::string& damaged_path, const std::string& out_path,
                                     bool overwrite_partial) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (out_path.empty()) return Status::InvalidArgument("the output path is empty");
  if (fs::exists(out_path, ec)) return Status::InvalidArgument(out_path + " already exists");
  const std::string tmp = out_path + ".partial";
  if (Status s = ClearPartialFile(tmp, overwrite_partial); !s.ok()) return s;
  RecoverReport report;
  Status put_error;
  {
    auto out = SetCache::Open(tmp);
    if (!out.ok()) return out.status();
    auto scan = ScanForDamage(damaged_path, [&](SetRecord&& rec) {
      if (!put_error.ok()) return;
      put_error = (*out)->Put(rec);
      if (put_error.ok()) ++report.recovered;
    });
    if (!scan.ok()) put_error = scan.status();
    if (put_error.ok()) {
      report.lost = std::move(scan->damaged);
      report.problems = std::move(scan->problems);
    }
  }  // closing the last connection checkpoints and removes the WAL
  if (!put_error.ok()) {
    RemovePartialFile(tmp);
    return put_error;
  }
  fs::rename(tmp, out_path, ec);
  if (ec) return Status::Internal("rename " + tmp + " -> " + out_path + ": " + ec.message());
  const fs::path parent = fs::absolute(fs::path(out_path)).parent_path();
  if (const int fd = ::open(parent.c_str(), O_DIRECTORY | O_RDONLY | O_CLOEXEC); fd >= 0) {
    ::fsync(fd);
    ::close(fd);
  }
  return report;
}

}  // namespace alignset::storage

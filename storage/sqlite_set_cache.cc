// SetCache on SQLite.
//
// Concurrency: one read-write connection behind a mutex. SQLite serializes
// writers anyway, a Get of a typical set (64 KiB at N = 4096) takes tens of
// microseconds, and the scheduler's single-flight keeps writes rare, so a
// connection pool would add failure modes (per-thread snapshots, pool
// sizing) for no measurable gain. The long whole-file operations (Verify,
// ExportTo, reading MergeFrom's source) open their own read-only connection:
// WAL lets them read a consistent snapshot without blocking the server.
//
// Durability: WAL with synchronous=NORMAL. A commit appends the transaction
// to the WAL; it becomes part of the database only once its commit frame is
// complete, and a checkpoint fsyncs the WAL before copying it back. A killed
// process therefore leaves every committed set intact and no trace of an
// uncommitted one (the OS still holds the written pages). Power loss can lose
// the last commits but never corrupts the file; for a cache that means a
// recompute, which is why NORMAL is the default and FULL (fsync on every
// commit) is an option.
#include <fcntl.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <ctime>
#include <filesystem>
#include <mutex>
#include <string>
#include <thread>
#include <utility>

#include "storage/blob_codec.h"
#include "storage/cache_recovery.h"
#include "storage/schema.h"
#include "storage/set_rows.h"
#include "storage/set_cache.h"
#include "storage/sqlite_handle.h"

namespace alignset::storage {
namespace {

constexpr const char* kKeyWhere =
    " WHERE n = ?1 AND dir_count = ?2 AND phi1 = ?3 AND phi2 = ?4 AND realization = ?5"
    " AND profile = ?6";
constexpr const char* kOrder = " ORDER BY n, dir_count, phi1, phi2, realization, profile";
constexpr size_t kMaxEngineName = 64;

bool Finite(double v) { return std::isfinite(v); }

Status ValidateRecord(const SetRecord& r) {
  Status s = ValidateKey(r.key);
  if (!s.ok()) return s;
  if (r.points.size() != r.key.n) {
    return Status::InvalidArgument("record for " + KeyToString(r.key) + " holds " +
                                   std::to_string(r.points.size()) + " points");
  }
  for (const Point2& p : r.points) {
    if (!(Finite(p.x) && Finite(p.y) && p.x >= 0.0 && p.x < 1.0 && p.y >= 0.0 && p.y < 1.0)) {
      return Status::InvalidArgument("record for " + KeyToString(r.key) +
                                     " has a point outside [0,1)^2");
    }
  }
  // SQLite stores NaN as NULL; reject it here with a clear message.
  if (!Finite(r.loss.total) || !Finite(r.loss.spectrum) || !Finite(r.loss.sw) ||
      !Finite(r.optimize_seconds) || r.optimize_seconds < 0.0 || r.iterations < 0) {
    return Status::InvalidArgument("record for " + KeyToString(r.key) +
                                   " has non-finite or negative metadata");
  }
  if (r.engine.size() > kMaxEngineName) return Status::InvalidArgument("engine name too long");
  return Status::Ok();
}

// Runs `fn` again while it reports Unavailable (SQLITE_BUSY), up to
// `timeout_ms`. Needed for the few steps where SQLite returns BUSY without
// consulting the busy handler (switching to WAL while another connection
// opens the same new file).
template <typename Fn>
Status RetryBusy(int timeout_ms, Fn fn) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::milliseconds(timeout_ms);
  for (;;) {
    Status s = fn();
    if (s.code() != Status::Code::kUnavailable || std::chrono::steady_clock::now() >= deadline) {
      return s;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
}

std::string Filter(const std::optional<uint32_t>& n, const std::optional<std::string>& profile) {
  std::string w;
  if (n) w += " WHERE n = ?1";
  if (profile) w += n ? " AND profile = ?2" : " WHERE profile = ?2";
  return w;
}

void BindFilter(Stmt& s, const std::optional<uint32_t>& n, const std::optional<std::string>& profile) {
  if (n) s.BindInt(1, *n);
  if (profile) s.BindText(2, *profile);
}

// file:PATH?mode=ro&immutable=1, with the characters a URI path may not
// hold percent-encoded.
std::string ImmutableUri(const std::string& path) {
  std::string out = "file:";
  for (unsigned char c : path) {
    if (c == '%' || c == '?' || c == '#' || c < 0x21 || c > 0x7e) {
      static const char* kHex = "0123456789ABCDEF";
      out += '%';
      out += kHex[c >> 4];
      out += kHex[c & 15];
    } else {
      out += static_cast<char>(c);
    }
  }
  return out + "?mode=ro&immutable=1";
}

Status FsyncPath(const std::string& path, bool directory) {
  const int fd = ::open(path.c_str(), (directory ? O_DIRECTORY : 0) | O_RDONLY | O_CLOEXEC);
  if (fd < 0) return Status::Internal("open " + path + " for fsync failed");
  const int rc = ::fsync(fd);
  ::close(fd);
  if (rc != 0) return Status::Internal("fsync " + path + " failed");
  return Status::Ok();
}

class SqliteSetCache final : public SetCache {
 public:
  SqliteSetCache(std::string path, Options options, Db db)
      : path_(std::move(path)), options_(options), db_(std::move(db)) {}

  Status Put(const SetRecord& record) override {
    if (options_.read_only) return Status::InvalidArgument("cache " + path_ + " is open read-only");
    Status s = ValidateRecord(record);
    if (!s.ok()) return s;
    // Packing and the checksum happen outside the lock.
    const std::vector<uint8_t> blob = PackPoints(record.points);
    const uint32_t crc = Crc32c(blob);
    std::lock_guard<std::mutex> lock(mu_);
    return PutLocked(record, blob, crc);
  }

  StatusOr<SetRecord> Get(const SetKey& key) override {
    Status s = ValidateKey(key);
    if (!s.ok()) return s;
    std::lock_guard<std::mutex> lock(mu_);
    return GetLocked(key);
  }

  StatusOr<bool> Contains(const SetKey& key) override {
    Status s = ValidateKey(key);
    if (!s.ok()) return s;
    std::lock_guard<std::mutex> lock(mu_);
    auto stmt = Stmt::Prepare(db_.get(), std::string("SELECT 1 FROM sets") + kKeyWhere);
    if (!stmt.ok()) return stmt.status();
    BindKey(*stmt, key);
    return stmt->Step();
  }

  StatusOr<std::vector<SetKey>> List(std::optional<uint32_t> n,
                                     std::optional<std::string> profile) override {
    std::lock_guard<std::mutex> lock(mu_);
    auto stmt = Stmt::Prepare(db_.get(), "SELECT n, dir_count, phi1, phi2, realization, profile FROM sets" +
                                             Filter(n, profile) + kOrder);
    if (!stmt.ok()) return stmt.status();
    BindFilter(*stmt, n, profile);
    std::vector<SetKey> keys;
    for (;;) {
      auto row = stmt->Step();
      if (!row.ok()) return row.status();
      if (!*row) return keys;
      keys.push_back(KeyFromRow(*stmt));
    }
  }

  StatusOr<std::vector<SetSummary>> ListSummaries(std::optional<uint32_t> n,
                                                  std::optional<std::string> profile) override {
    std::lock_guard<std::mutex> lock(mu_);
    // length() of a blob is read from the record header: no overflow page
    // is touched.
    auto stmt = Stmt::Prepare(
        db_.get(),
        "SELECT n, dir_count, phi1, phi2, realization, profile, loss_total, loss_spectrum, "
        "loss_sw, iterations, optimize_seconds, engine, created_unix, algorithm_version, "
        "length(points) FROM sets" +
            Filter(n, profile) + kOrder);
    if (!stmt.ok()) return stmt.status();
    BindFilter(*stmt, n, profile);
    std::vector<SetSummary> out;
    for (;;) {
      auto row = stmt->Step();
      if (!row.ok()) return row.status();
      if (!*row) return out;
      SetSummary s;
      s.key = KeyFromRow(*stmt);
      MetadataFromRow(*stmt, &s);
      s.bytes = stmt->Int(14);
      out.push_back(std::move(s));
    }
  }

  StatusOr<CacheStats> Stats() override {
    std::lock_guard<std::mutex> lock(mu_);
    auto stmt = Stmt::Prepare(db_.get(),
                              "SELECT COUNT(*), COALESCE(SUM(length(points)), 0), "
                              "COALESCE(SUM(dir_count = 1), 0), COALESCE(SUM(dir_count = 2), 0) "
                              "FROM sets");
    if (!stmt.ok()) return stmt.status();
    auto row = stmt->Step();
    if (!row.ok() && row.status().code() == Status::Code::kDataLoss) return DamagedStats();
    if (!row.ok()) return row.status();
    CacheStats st;
    st.sets = stmt->Int(0);
    st.bytes = stmt->Int(1);
    st.one_direction_sets = stmt->Int(2);
    st.two_direction_sets = stmt->Int(3);
    return st;
  }

  StatusOr<VerifyReport> Verify() override {
    auto scan = ScanForDamage(path_);
    if (!scan.ok()) return scan.status();
    VerifyReport report;
    report.checked = scan->readable + static_cast<int64_t>(scan->damaged.size());
    report.corrupt = std::move(scan->damaged);
    report.problems = std::move(scan->problems);
    return report;
  }

  StatusOr<MergeReport> MergeFrom(const std::string& other_path) override {
    if (options_.read_only) return Status::InvalidArgument("cache " + path_ + " is open read-only");
    auto other = OpenReader(other_path);
    if (!other.ok()) return other.status();
    auto version = SchemaVersion(*other);
    if (!version.ok()) return version.status();
    // Versions 1 and 2 lack the realization column (their sets are
    // realization 0); a later migration that changes the columns must teach
    // this reader its layout too.
    if (*version < 1) return Status::InvalidArgument(other_path + " holds no alignset cache");
    if (*version > LatestSchemaVersion()) {
      return Status::InvalidArgument(other_path + " has schema version " + std::to_string(*version) +
                                     ", newer than this build understands");
    }
    auto tx = Transaction::Begin(*other, Transaction::Kind::kRead);
    if (!tx.ok()) return tx.status();
    const bool before_realizations = *version < 3;
    auto stmt = Stmt::Prepare(other->get(), std::string("SELECT ") +
                                                 (before_realizations ? kColumnsBeforeRealizations
                                                                      : kColumns) +
                                                 " FROM sets" +
                                                 (before_realizations
                                                      ? " ORDER BY n, dir_count, phi1, phi2, profile"
                                                      : kOrder));
    if (!stmt.ok()) return stmt.status();
    MergeReport report;
    for (;;) {
      auto row = stmt->Step();
      if (!row.ok()) return row.status();
      if (!*row) return report;
      auto rec = RecordFromRow(*stmt);
      if (!rec.ok()) {
        ++report.skipped_corrupt;
        continue;
      }
      std::lock_guard<std::mutex> lock(mu_);
      auto mine = GetLocked(rec->key);
      if (mine.ok()) {
        ++report.skipped_existing;
        continue;
      }
      // A missing row is added; a corrupt one of ours is replaced by the
      // verified copy.
      if (mine.status().code() != Status::Code::kNotFound &&
          mine.status().code() != Status::Code::kDataLoss) {
        return mine.status();
      }
      const std::vector<uint8_t> blob = PackPoints(rec->points);
      Status s = PutLocked(*rec, blob, Crc32c(blob));
      if (!s.ok()) return s;
      ++report.added;
    }
  }

  Status ExportTo(const std::string& path) override {
    namespace fs = std::filesystem;
    std::error_code ec;
    if (path.empty()) return Status::InvalidArgument("export path is empty");
    if (fs::exists(path, ec)) return Status::InvalidArgument(path + " already exists");
    // VACUUM INTO neither fsyncs its output nor is atomic against a crash,
    // so it writes a temporary file that is synced and then renamed.
    const std::string tmp = path + ".partial";
    fs::remove(tmp, ec);
    {
      auto reader = OpenReader(path_);
      if (!reader.ok()) return reader.status();
      auto stmt = Stmt::Prepare(reader->get(), "VACUUM INTO ?1");
      if (!stmt.ok()) return stmt.status();
      stmt->BindText(1, tmp);
      Status s = stmt->Run();
      if (!s.ok()) {
        fs::remove(tmp, ec);
        return s;
      }
    }
    Status s = FsyncPath(tmp, false);
    if (s.ok() && fs::exists(path, ec)) s = Status::InvalidArgument(path + " already exists");
    if (s.ok()) {
      fs::rename(tmp, path, ec);
      if (ec) s = Status::Internal("rename " + tmp + " -> " + path + ": " + ec.message());
    }
    if (!s.ok()) {
      fs::remove(tmp, ec);
      return s;
    }
    const fs::path parent = fs::absolute(fs::path(path)).parent_path();
    return FsyncPath(parent.string(), true);
  }

  Status Delete(const SetKey& key) override {
    if (options_.read_only) return Status::InvalidArgument("cache " + path_ + " is open read-only");
    if (Status s = ValidateKey(key); !s.ok()) return s;
    std::lock_guard<std::mutex> lock(mu_);
    auto tx = Transaction::Begin(db_, Transaction::Kind::kWrite);
    if (!tx.ok()) return tx.status();
    {
      auto stmt = Stmt::Prepare(db_.get(), std::string("DELETE FROM sets") + kKeyWhere);
      if (!stmt.ok()) return stmt.status();
      BindKey(*stmt, key);
      if (Status s = stmt->Run(); !s.ok()) return s;
    }
    if (sqlite3_changes(db_.get()) == 0) return Status::NotFound("no cached set for " + KeyToString(key));
    return tx->Commit();
  }

  StatusOr<FileSpace> Space() override {
    std::lock_guard<std::mutex> lock(mu_);
    FileSpace f;
    for (auto [sql, out] : {std::pair{"PRAGMA page_size", &f.page_size},
                            std::pair{"PRAGMA page_count", &f.page_count},
                            std::pair{"PRAGMA freelist_count", &f.freelist_count}}) {
      auto v = db_.QueryText(sql);
      if (!v.ok()) return v.status();
      *out = std::stoll(*v);
    }
    return f;
  }

  Status EnableIncrementalVacuum() override {
    if (options_.read_only) return Status::InvalidArgument("cache " + path_ + " is open read-only");
    {
      std::lock_guard<std::mutex> lock(mu_);
      auto mode = db_.QueryText("PRAGMA auto_vacuum");
      if (!mode.ok()) return mode.status();
      if (*mode == "2") return Status::Ok();  // incremental already
      if (Status s = db_.Exec("PRAGMA auto_vacuum = INCREMENTAL"); !s.ok()) return s;
    }
    // The switch takes effect only through a VACUUM, which rebuilds the
    // file. On a connection of its own: the server's reads (WAL snapshots)
    // go on; its writes wait (busy timeout) or are served not stored.
    auto db = Db::Open(path_, SQLITE_OPEN_READWRITE | SQLITE_OPEN_NOMUTEX, options_.busy_timeout_ms);
    if (!db.ok()) return db.status();
    if (Status s = db->Exec("PRAGMA auto_vacuum = INCREMENTAL"); !s.ok()) return s;
    return RetryBusy(options_.busy_timeout_ms, [&] { return db->Exec("VACUUM"); });
  }

  StatusOr<int64_t> IncrementalVacuum(int64_t pages) override {
    if (options_.read_only) return Status::InvalidArgument("cache " + path_ + " is open read-only");
    std::lock_guard<std::mutex> lock(mu_);
    if (Status s = db_.Exec("PRAGMA incremental_vacuum(" + std::to_string(pages) + ")"); !s.ok()) return s;
    auto left = db_.QueryText("PRAGMA freelist_count");
    if (!left.ok()) return left.status();
    return std::stoll(*left);
  }

  Status ProbeWrite() override {
    if (options_.read_only) return Status::InvalidArgument("cache " + path_ + " is open read-only");
    std::lock_guard<std::mutex> lock(mu_);
    if (sqlite3_db_readonly(db_.get(), "main") == 1) {
      return Status::InvalidArgument(path_ + " can only be opened read-only (file permissions, "
                                     "a read-only file system, or a newer file format)");
    }
    auto tx = Transaction::Begin(db_, Transaction::Kind::kWrite);
    if (!tx.ok()) return tx.status();
    // user_version is not used by the schema (schema_version is a table):
    // writing its own value back changes nothing but dirties page 1, so the
    // commit really writes.
    auto version = db_.QueryText("PRAGMA user_version");
    if (!version.ok()) return version.status();
    Status s = db_.Exec("PRAGMA user_version = " + *version);
    if (!s.ok()) return s;
    return tx->Commit();
  }

 private:
  // The figures of the rows that can still be read, from a damage scan.
  StatusOr<CacheStats> DamagedStats() const {
    CacheStats st;
    st.damaged = true;
    auto scan = ScanForDamage(path_, [&](SetRecord&& r) {
      ++st.sets;
      st.bytes += static_cast<int64_t>(r.points.size() * kBytesPerPoint);
      (r.key.dirs.count == 1 ? st.one_direction_sets : st.two_direction_sets) += 1;
    });
    if (!scan.ok()) return scan.status();
    return st;
  }

  StatusOr<Db> OpenReader(const std::string& path) const {
    if (options_.immutable && path == path_) {
      return Db::Open(ImmutableUri(path), SQLITE_OPEN_READONLY | SQLITE_OPEN_NOMUTEX | SQLITE_OPEN_URI,
                      options_.busy_timeout_ms);
    }
    return Db::Open(path, SQLITE_OPEN_READONLY | SQLITE_OPEN_NOMUTEX, options_.busy_timeout_ms);
  }

  Status PutLocked(const SetRecord& r, const std::vector<uint8_t>& blob, uint32_t crc) {
    auto tx = Transaction::Begin(db_, Transaction::Kind::kWrite);
    if (!tx.ok()) return tx.status();
    {
      auto stmt = Stmt::Prepare(db_.get(), std::string("INSERT OR REPLACE INTO sets (") + kColumns +
                                               ") VALUES (?1, ?2, ?3, ?4, ?5, ?6, ?7, ?8, ?9, "
                                               "?10, ?11, ?12, ?13, ?14, ?15, ?16)");
      if (!stmt.ok()) return stmt.status();
      BindKey(*stmt, r.key);
      stmt->BindDouble(7, r.loss.total);
      stmt->BindDouble(8, r.loss.spectrum);
      stmt->BindDouble(9, r.loss.sw);
      stmt->BindInt(10, r.iterations);
      stmt->BindDouble(11, r.optimize_seconds);
      stmt->BindText(12, r.engine);
      stmt->BindInt(13, r.created_unix != 0 ? r.created_unix : static_cast<int64_t>(std::time(nullptr)));
      stmt->BindInt(14, r.algorithm_version);
      stmt->BindInt(15, crc);
      stmt->BindBlob(16, blob);
      Status s = stmt->Run();
      if (!s.ok()) return s;
    }
    return tx->Commit();
  }

  StatusOr<SetRecord> GetLocked(const SetKey& key) {
    auto stmt = Stmt::Prepare(db_.get(), std::string("SELECT ") + kColumns + " FROM sets" + kKeyWhere);
    if (!stmt.ok()) return stmt.status();
    BindKey(*stmt, key);
    auto row = stmt->Step();
    if (!row.ok()) return row.status();
    if (!*row) return Status::NotFound("no cached set for " + KeyToString(key));
    return RecordFromRow(*stmt);
  }

  const std::string path_;
  const Options options_;
  std::mutex mu_;  // guards db_
  Db db_;
};

}  // namespace

StatusOr<std::unique_ptr<SetCache>> SetCache::Open(const std::string& path, const Options& options) {
  if (path.empty() || path == ":memory:" || path.rfind("file:", 0) == 0) {
    return Status::InvalidArgument("the set cache needs a plain file path, got '" + path + "'");
  }
  if (options.busy_timeout_ms < 0) return Status::InvalidArgument("busy_timeout_ms must be >= 0");
  Options opts = options;
  if (opts.immutable) opts.read_only = true;
  int flags = SQLITE_OPEN_NOMUTEX | (opts.read_only ? SQLITE_OPEN_READONLY
                                                    : SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE);
  std::string name = path;
  if (opts.immutable) {
    // An immutable file that is not there would otherwise open as empty.
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec)) return Status::NotFound("open " + path + ": no such file");
    flags |= SQLITE_OPEN_URI;
    name = ImmutableUri(path);
  }
  auto db = Db::Open(name, flags, opts.busy_timeout_ms);
  if (!db.ok()) return db.status();
  if (opts.read_only) {
    auto version = SchemaVersion(*db);
    if (!version.ok()) return version.status();
    if (*version < 1) return Status::NotFound(path + " holds no alignset cache");
    if (*version > LatestSchemaVersion()) {
      return Status::InvalidArgument(path + " has schema version " + std::to_string(*version) +
                                     ", newer than this build understands");
    }
  } else {
    Status s = RetryBusy(options.busy_timeout_ms, [&]() -> Status {
      auto mode = db->QueryText("PRAGMA journal_mode = WAL");
      if (!mode.ok()) return mode.status();
      if (*mode != "wal") return Status::Internal(path + ": cannot use WAL (journal mode " + *mode + ")");
      return Status::Ok();
    });
    if (!s.ok()) return s;
    s = db->Exec(options.full_sync ? "PRAGMA synchronous = FULL" : "PRAGMA synchronous = NORMAL");
    if (!s.ok()) return s;
    // Truncate the WAL after a checkpoint instead of keeping it at its
    // largest size (one 2^20-point set alone is 16 MiB).
    s = db->Exec("PRAGMA journal_size_limit = 67108864");
    if (!s.ok()) return s;
    s = RetryBusy(options.busy_timeout_ms, [&] { return Migrate(*db, Migrations()); });
    if (!s.ok()) return s;
  }
  return std::unique_ptr<SetCache>(new SqliteSetCache(path, opts, std::move(db).value()));
}

}  // namespace alignset::storage

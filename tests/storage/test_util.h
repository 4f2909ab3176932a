#pragma once

#include <gtest/gtest.h>
#include <sqlite3.h>
#include <stdlib.h>

#include <bit>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>

#include "core/util/hash.h"
#include "storage/set_cache.h"

namespace alignset::storage::testing {

// A fresh directory under $TMPDIR, removed with everything in it.
class TempDir {
 public:
  TempDir() {
    std::string tmpl = (std::filesystem::temp_directory_path() / "alignset-storage-XXXXXX").string();
    char* p = ::mkdtemp(tmpl.data());
    if (p != nullptr) path_ = p;
  }
  ~TempDir() {
    std::error_code ec;
    if (!path_.empty()) std::filesystem::remove_all(path_, ec);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  const std::string& path() const { return path_; }
  std::string File(const std::string& name) const { return path_ + "/" + name; }

 private:
  std::string path_;
};

inline SetKey Key1(uint32_t n, int phi, std::string profile = "0123456789abcdef") {
  SetKey k;
  k.n = n;
  k.dirs = {1, phi, phi};
  k.profile = std::move(profile);
  return k;
}

inline SetKey Key2(uint32_t n, int phi1, int phi2, std::string profile = "0123456789abcdef") {
  SetKey k;
  k.n = n;
  k.dirs = {2, phi1, phi2};
  k.profile = std::move(profile);
  return k;
}

// The key's realization r (0 is the one every key always had).
inline SetKey WithRealization(SetKey k, uint32_t r) {
  k.realization = r;
  return k;
}

inline uint64_t KeyHash(const SetKey& k) {
  uint64_t h = HashCombine(k.n, static_cast<uint64_t>(k.dirs.count));
  h = HashCombine(h, static_cast<uint64_t>(k.dirs.phi1));
  h = HashCombine(h, static_cast<uint64_t>(k.dirs.phi2));
  for (char c : k.profile) h = HashCombine(h, static_cast<unsigned char>(c));
  return h;
}

// Points that are a pure function of (key, generation): a reader can tell
// whether a row's blob and metadata come from the same write.
inline PointSet MakePoints(const SetKey& key, uint64_t generation) {
  Pcg32 rng(HashCombine(KeyHash(key), generation));
  PointSet p(key.n);
  for (Point2& q : p) {
    q.x = rng.NextDouble();
    q.y = rng.NextDouble();
  }
  return p;
}

// A record whose metadata also encodes the generation (in `iterations`).
inline SetRecord MakeRecord(const SetKey& key, int generation = 0) {
  SetRecord r;
  r.key = key;
  r.points = MakePoints(key, static_cast<uint64_t>(generation));
  r.loss = {1.5 + generation, 0.5, 0.1};
  r.iterations = generation;
  r.optimize_seconds = 0.25 * (generation + 1);
  r.engine = "direct";
  r.created_unix = 1700000000 + generation;
  return r;
}

inline bool BitEqual(const PointSet& a, const PointSet& b) {
  if (a.size() != b.size()) return false;
  for (size_t i = 0; i < a.size(); ++i) {
    if (std::bit_cast<uint64_t>(a[i].x) != std::bit_cast<uint64_t>(b[i].x) ||
        std::bit_cast<uint64_t>(a[i].y) != std::bit_cast<uint64_t>(b[i].y)) {
      return false;
    }
  }
  return true;
}

// Opens a cache that the test needs (a failure is reported; null then).
inline std::unique_ptr<SetCache> MustOpen(const std::string& path, SetCache::Options o = {}) {
  auto c = SetCache::Open(path, o);
  EXPECT_TRUE(c.ok()) << c.status().ToString();
  return c.ok() ? std::move(c).value() : nullptr;
}

// Raw access with the plain SQLite API, as an outside tool (or damage)
// would modify the file.
class RawDb {
 public:
  explicit RawDb(const std::string& path) { sqlite3_open(path.c_str(), &db_); }
  ~RawDb() { sqlite3_close(db_); }
  RawDb(const RawDb&) = delete;
  RawDb& operator=(const RawDb&) = delete;
  sqlite3* get() const { return db_; }

  bool Exec(const std::string& sql) {
    return sqlite3_exec(db_, sql.c_str(), nullptr, nullptr, nullptr) == SQLITE_OK;
  }
  // First column of the first row as text ("" when there is none).
  std::string Text(const std::string& sql) {
    sqlite3_stmt* s = nullptr;
    std::string out;
    if (sqlite3_prepare_v2(db_, sql.c_str(), -1, &s, nullptr) == SQLITE_OK &&
        sqlite3_step(s) == SQLITE_ROW && sqlite3_column_text(s, 0) != nullptr) {
      out = reinterpret_cast<const char*>(sqlite3_column_text(s, 0));
    }
    sqlite3_finalize(s);
    return out;
  }
  int64_t Int(const std::string& sql) {
    const std::string t = Text(sql);
    return t.empty() ? 0 : std::stoll(t);
  }

  // XORs one byte of the stored blob of `key` with `mask`, leaving the
  // checksum column alone. Returns false when there is no such row.
  bool FlipBlobByte(const SetKey& key, size_t offset, uint8_t mask = 0x01) {
    sqlite3_stmt* s = nullptr;
    sqlite3_prepare_v2(db_, "SELECT points FROM sets WHERE n=?1 AND dir_count=?2 AND phi1=?3 "
                            "AND phi2=?4 AND profile=?5 AND realization=?6", -1, &s, nullptr);
    Bind(s, key);
    std::string blob;
    if (sqlite3_step(s) == SQLITE_ROW) {
      blob.assign(static_cast<const char*>(sqlite3_column_blob(s, 0)), sqlite3_column_bytes(s, 0));
    }
    sqlite3_finalize(s);
    if (blob.empty() || offset >= blob.size()) return false;
    blob[offset] = static_cast<char>(blob[offset] ^ mask);
    return SetBlob(key, blob);
  }

  bool SetBlob(const SetKey& key, const std::string& blob) {
    sqlite3_stmt* s = nullptr;
    sqlite3_prepare_v2(db_, "UPDATE sets SET points = ?7 WHERE n=?1 AND dir_count=?2 AND phi1=?3 "
                            "AND phi2=?4 AND profile=?5 AND realization=?6", -1, &s, nullptr);
    Bind(s, key);
    sqlite3_bind_blob(s, 7, blob.data(), static_cast<int>(blob.size()), SQLITE_TRANSIENT);
    const bool ok = sqlite3_step(s) == SQLITE_DONE && sqlite3_changes(db_) == 1;
    sqlite3_finalize(s);
    return ok;
  }

 private:
  static void Bind(sqlite3_stmt* s, const SetKey& key) {
    sqlite3_bind_int64(s, 1, key.n);
    sqlite3_bind_int(s, 2, key.dirs.count);
    sqlite3_bind_int(s, 3, key.dirs.phi1);
    sqlite3_bind_int(s, 4, key.dirs.phi2);
    sqlite3_bind_text(s, 5, key.profile.c_str(), -1, SQLITE_TRANSIENT);
    sqlite3_bind_int64(s, 6, key.realization);
  }
  sqlite3* db_ = nullptr;
};

}  // namespace alignset::storage::testing

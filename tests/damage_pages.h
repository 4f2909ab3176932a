#pragma once

// Page-level damage for tests: finds the pages of a table's B-tree in an
// SQLite file (format: https://www.sqlite.org/fileformat2.html, section 1.6)
// and overwrites a page's header, as a torn write or a bad sector would.
// The file must be closed and checkpointed (no -wal) first.
#include <sqlite3.h>

#include <cstdint>
#include <fstream>
#include <string>
#include <utility>
#include <vector>

namespace alignset::testing {

struct TablePages {
  uint32_t page_size = 0;
  uint32_t root = 0;
  std::vector<uint32_t> leaves;  // in key order
  // Rowids on each leaf, parallel to `leaves`.
  std::vector<std::vector<int64_t>> rowids;
};

inline std::vector<uint8_t> ReadPage(const std::string& path, uint32_t page_size, uint32_t page) {
  std::ifstream in(path, std::ios::binary);
  std::vector<uint8_t> bytes(page_size);
  in.seekg(static_cast<std::streamoff>(page - 1) * page_size);
  in.read(reinterpret_cast<char*>(bytes.data()), page_size);
  return bytes;
}

inline uint32_t Be(const uint8_t* p, int n) {
  uint32_t v = 0;
  for (int i = 0; i < n; ++i) v = (v << 8) | p[i];
  return v;
}

inline int64_t Varint(const uint8_t* p, int* len) {
  uint64_t v = 0;
  for (int i = 0; i < 9; ++i) {
    if (i == 8) {
      v = (v << 8) | p[i];
      *len = 9;
      return static_cast<int64_t>(v);
    }
    v = (v << 7) | (p[i] & 0x7f);
    if (!(p[i] & 0x80)) {
      *len = i + 1;
      return static_cast<int64_t>(v);
    }
  }
  return static_cast<int64_t>(v);
}

inline void Walk(const std::string& path, uint32_t page_size, uint32_t page, TablePages* out) {
  const std::vector<uint8_t> bytes = ReadPage(path, page_size, page);
  const size_t h = page == 1 ? 100 : 0;
  const uint8_t type = bytes[h];
  const uint32_t cells = Be(&bytes[h + 3], 2);
  if (type == 0x05) {  // interior table page: left children, then the right-most one
    for (uint32_t i = 0; i < cells; ++i) {
      const uint32_t cell = Be(&bytes[h + 12 + 2 * i], 2);
      Walk(path, page_size, Be(&bytes[cell], 4), out);
    }
    Walk(path, page_size, Be(&bytes[h + 8], 4), out);
  } else if (type == 0x0d) {  // leaf table page: payload size, rowid, payload
    out->leaves.push_back(page);
    std::vector<int64_t> rowids;
    for (uint32_t i = 0; i < cells; ++i) {
      const uint32_t cell = Be(&bytes[h + 8 + 2 * i], 2);
      int len = 0;
      Varint(&bytes[cell], &len);
      int len2 = 0;
      rowids.push_back(Varint(&bytes[cell + len], &len2));
    }
    out->rowids.push_back(std::move(rowids));
  }
}

// The pages of `table` in the closed database at `path`.
inline TablePages FindTablePages(const std::string& path, const std::string& table) {
  TablePages t;
  sqlite3* db = nullptr;
  if (sqlite3_open_v2(path.c_str(), &db, SQLITE_OPEN_READONLY, nullptr) == SQLITE_OK) {
    sqlite3_stmt* st = nullptr;
    sqlite3_prepare_v2(db, "SELECT rootpage FROM sqlite_master WHERE type = 'table' AND name = ?1", -1, &st, nullptr);
    sqlite3_bind_text(st, 1, table.c_str(), -1, SQLITE_TRANSIENT);
    if (sqlite3_step(st) == SQLITE_ROW) t.root = static_cast<uint32_t>(sqlite3_column_int(st, 0));
    sqlite3_finalize(st);
  }
  sqlite3_close(db);
  std::ifstream in(path, std::ios::binary);
  uint8_t header[100] = {};
  in.read(reinterpret_cast<char*>(header), 100);
  t.page_size = Be(&header[16], 2);
  if (t.page_size == 1) t.page_size = 65536;
  if (t.root != 0) Walk(path, t.page_size, t.root, &t);
  return t;
}

// Overwrites the B-tree page header of `page` (type byte, freeblock, cell
// count) with garbage: SQLite reports SQLITE_CORRUPT for any read through it.
inline void DamagePageHeader(const std::string& path, uint32_t page_size, uint32_t page) {
  std::fstream f(path, std::ios::in | std::ios::out | std::ios::binary);
  f.seekp(static_cast<std::streamoff>(page - 1) * page_size + (page == 1 ? 100 : 0));
  const char garbage[5] = {'\x42', '\xff', '\xff', '\xff', '\xff'};
  f.write(garbage, sizeof(garbage));
}

}  // namespace alignset::testing

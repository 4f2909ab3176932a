// A cache file handed to `cache verify`, `cache merge` or a server at start,
// on any bytes: written to a file, opened read-only (immutable, as a replica
// opens it) and writable (a copy), then listed, verified, every listed row
// read, and merged into a fresh cache. Statuses, never a crash; whatever the
// merge copied must read back verified.
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "storage/set_cache.h"

namespace {

std::string Dir() {
  static const std::string dir = [] {
    const std::string d = std::filesystem::temp_directory_path() / ("alignset-fuzz-" + std::to_string(getpid()));
    std::filesystem::create_directories(d);
    return d;
  }();
  return dir;
}

void Write(const std::string& path, const uint8_t* data, size_t size) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
}

void Clear(const std::string& path) {
  for (const char* suffix : {"", "-wal", "-shm", "-journal"}) std::filesystem::remove(path + suffix);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  namespace st = alignset::storage;
  const std::string file = Dir() + "/input.sqlite", copy = Dir() + "/copy.sqlite", target = Dir() + "/target.sqlite";
  Clear(file), Clear(copy), Clear(target);
  Write(file, data, size);
  Write(copy, data, size);
  st::SetCache::Options ro;
  ro.immutable = true;
  ro.busy_timeout_ms = 10;
  if (auto cache = st::SetCache::Open(file, ro); cache.ok()) {
    (void)(*cache)->Stats();
    (void)(*cache)->Verify();
    if (auto keys = (*cache)->List(); keys.ok()) {
      for (size_t i = 0; i < keys->size() && i < 64; ++i) (void)(*cache)->Get((*keys)[i]);
    }
  }
  st::SetCache::Options rw;
  rw.busy_timeout_ms = 10;
  if (auto cache = st::SetCache::Open(copy, rw); cache.ok()) (void)(*cache)->Verify();
  if (auto fresh = st::SetCache::Open(target, rw); fresh.ok()) {
    if (auto merged = (*fresh)->MergeFrom(file); merged.ok()) {
      auto keys = (*fresh)->List();
      if (!keys.ok()) std::abort();
      for (const auto& key : *keys) {
        if (!(*fresh)->Get(key).ok()) std::abort();  // a merged row is a verified row
      }
    }
  }
  Clear(file), Clear(copy), Clear(target);
  return 0;
}

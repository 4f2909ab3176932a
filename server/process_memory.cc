#include "server/process_memory.h"

#include <cstdio>
#include <cstdlib>
#include <cstring>

#if defined(ALIGNSET_WITH_JEMALLOC)
#include <jemalloc/jemalloc.h>
#elif defined(__GLIBC__)
#include <malloc.h>
#endif

namespace alignset::server {
namespace {

void ReadStatus(ProcessMemory* m) {
  std::FILE* f = std::fopen("/proc/self/status", "r");
  if (!f) return;
  const struct {
    const char* name;
    int64_t* out;
  } fields[] = {{"VmRSS:", &m->resident_bytes},
                {"RssAnon:", &m->resident_anonymous_bytes},
                {"RssFile:", &m->resident_file_bytes}};
  char line[256];
  while (std::fgets(line, sizeof line, f)) {
    for (const auto& field : fields) {
      const size_t len = std::strlen(field.name);
      long long kb = 0;
      if (std::strncmp(line, field.name, len) == 0 && std::sscanf(line + len, "%lld", &kb) == 1) {
        *field.out = kb * 1024;
      }
    }
  }
  std::fclose(f);
}

#if defined(ALIGNSET_WITH_JEMALLOC)
int64_t JemallocStat(const char* name) {
  size_t value = 0, len = sizeof value;
  return mallctl(name, &value, &len, nullptr, 0) == 0 ? static_cast<int64_t>(value) : 0;
}
#endif

}  // namespace

ProcessMemory ReadProcessMemory() {
  ProcessMemory m;
  ReadStatus(&m);
#if defined(ALIGNSET_WITH_JEMALLOC)
  // jemalloc's statistics are a snapshot taken when the epoch advances.
  uint64_t epoch = 1;
  size_t epoch_len = sizeof epoch;
  mallctl("epoch", &epoch, &epoch_len, &epoch, epoch_len);
  m.heap_allocated_bytes = JemallocStat("stats.allocated");
  m.heap_free_bytes = JemallocStat("stats.resident") - m.heap_allocated_bytes;
  // "5.3.0-0-g<commit>": the release is what an operator compares.
  const char* version = nullptr;
  size_t version_len = sizeof version;
  std::string release = mallctl("version", &version, &version_len, nullptr, 0) == 0 && version ? version : "?";
  m.allocator = "jemalloc " + release.substr(0, release.find('-'));
#elif defined(__GLIBC__) && (__GLIBC__ > 2 || (__GLIBC__ == 2 && __GLIBC_MINOR__ >= 33))
  // mallinfo2 walks every arena under its lock: cheap at a metrics call's
  // rate, not something to call per request.
  const struct mallinfo2 mi = mallinfo2();
  m.heap_allocated_bytes = static_cast<int64_t>(mi.uordblks + mi.hblkhd);
  m.heap_free_bytes = static_cast<int64_t>(mi.fordblks);
  m.allocator = "glibc";
#endif
  return m;
}

std::string LimitAllocatorKeeping(int max_arenas) {
#if !defined(ALIGNSET_WITH_JEMALLOC) && defined(__GLIBC__)
  if (std::getenv("MALLOC_ARENA_MAX") || std::getenv("GLIBC_TUNABLES")) return "";
  if (mallopt(M_ARENA_MAX, max_arenas) != 1) return "";
  return "glibc malloc: at most " + std::to_string(max_arenas) + " arenas";
#else
  (void)max_arenas;
  return "";
#endif
}

int MallocArenas() {
#if !defined(ALIGNSET_WITH_JEMALLOC) && defined(__GLIBC__)
  char* text = nullptr;
  size_t size = 0;
  std::FILE* f = open_memstream(&text, &size);
  if (!f) return -1;
  const bool ok = malloc_info(0, f) == 0;
  std::fclose(f);
  int arenas = 0;
  // One <heap nr="..."> element an arena.
  for (const char* p = text; ok && (p = std::strstr(p, "<heap nr=")) != nullptr; ++p) ++arenas;
  std::free(text);
  return ok ? arenas : -1;
#else
  return -1;
#endif
}

}  // namespace alignset::server

#pragma once

#include <cstdint>
#include <string>

namespace alignset::server {

// The process's memory as the kernel and the allocator see it: what the
// server's own caches hold is reported beside it (GetMetrics), so that
// growth can be put down to a bounded cache or to the allocator's keeping.
struct ProcessMemory {
  int64_t resident_bytes = 0;            // VmRSS of /proc/self/status; 0 when unreadable
  int64_t resident_anonymous_bytes = 0;  // RssAnon: the heap, thread stacks
  int64_t resident_file_bytes = 0;       // RssFile: code, libraries, mapped files
  // The allocator's figures: bytes handed out, and what it holds beyond them
  // (jemalloc: resident pages not allocated; glibc: free chunks).
  int64_t heap_allocated_bytes = 0;
  int64_t heap_free_bytes = 0;
  std::string allocator;  // "jemalloc <version>" or "glibc"
};

ProcessMemory ReadProcessMemory();

}  // namespace alignset::server

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

// Glibc's malloc, left to itself, gives each busy thread an arena of its own
// (up to eight per core), and each arena keeps the free holes between its
// live blocks: with the server's many gRPC threads the 2-hour soak's resident
// memory grew 4 MB an hour, all of it free chunks the allocator kept while
// the program's own allocations stayed flat (docs/operations.md "Memory").
// This caps the arenas at `max_arenas`, so that threads share them and reuse
// each other's holes. It does nothing where the operator chose
// (MALLOC_ARENA_MAX or GLIBC_TUNABLES set), under jemalloc, or off glibc.
// Call once at the start, before other threads exist. Returns what it set,
// for the log ("" when it left the allocator alone).
std::string LimitAllocatorKeeping(int max_arenas);

// How many arenas glibc's malloc has made so far (from malloc_info); -1
// under jemalloc or off glibc.
int MallocArenas();

}  // namespace alignset::server

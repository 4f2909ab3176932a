#pragma once

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <thread>
#include <vector>

namespace alignset::render {

// fn(i) for i in [0, count) on `threads` threads (the caller is one), handed
// out in blocks of 64 so that uneven pixels (edges cost more) balance.
template <typename Fn>
void ParallelFor(size_t count, int threads, const Fn& fn) {
  std::atomic<size_t> next{0};
  auto work = [&] {
    for (size_t i; (i = next.fetch_add(64)) < count;) {
      for (size_t j = i; j < std::min(count, i + 64); ++j) fn(j);
    }
  };
  std::vector<std::thread> pool;
  for (int t = 1; t < std::max(1, threads); ++t) pool.emplace_back(work);
  work();
  for (std::thread& t : pool) t.join();
}

}  // namespace alignset::render

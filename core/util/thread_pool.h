#pragma once

#include <atomic>
#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace alignset {

// A fixed set of worker threads for data-parallel loops. The engines own one
// each so that the thread count an optimization runs with is exactly what was
// configured (several optimizations side by side do not oversubscribe).
//
// An optimizer iteration runs a dozen parallel loops a few tens of
// microseconds apart. Putting the workers to sleep between them cost about a
// tenth of an iteration at N = 4096 (futex wake-ups and context switches),
// so a worker that just finished a loop, and the caller waiting for the
// workers, first spin for up to kSpinMicroseconds and only then block.
// Longer gaps (between optimizations, an idle server) still sleep. The spin
// yields between bursts, so that on an oversubscribed machine the thread
// being waited for can run (two 2-thread optimizations on 2 cores: 4.9 s
// with a pure spin, 3.1 s with the yield, 3.4 s one after the other).
class ThreadPool {
 public:
  static constexpr int kSpinMicroseconds = 100;

  // `threads` <= 0 means one per hardware thread.
  explicit ThreadPool(int threads);
  ~ThreadPool();
  ThreadPool(const ThreadPool&) = delete;
  ThreadPool& operator=(const ThreadPool&) = delete;

  int size() const { return static_cast<int>(workers_.size()) + 1; }

  // Splits [0, n) into contiguous chunks and calls fn(begin, end, worker)
  // for each, worker in [0, size()). The calling thread takes part. Returns
  // when every chunk is done. Not reentrant.
  void ParallelFor(size_t n, const std::function<void(size_t, size_t, int)>& fn);

 private:
  void WorkerLoop(int index);
  // Spins until pred() holds or the spin time is up; true if it holds.
  template <typename Pred>
  static bool SpinUntil(Pred pred);

  std::vector<std::thread> workers_;
  std::mutex mu_;
  std::condition_variable start_cv_;
  std::condition_variable done_cv_;
  // Published by a release increment of generation_ (under mu_, so a
  // worker that checked the generation under mu_ cannot miss the notify).
  const std::function<void(size_t, size_t, int)>* job_ = nullptr;
  size_t job_n_ = 0;
  std::atomic<uint64_t> generation_{0};
  std::atomic<int> pending_{0};
  std::atomic<bool> stop_{false};
};

// Chunk [begin, end) of worker `w` out of `workers` for a loop of n items.
inline void ChunkBounds(size_t n, int w, int workers, size_t* begin, size_t* end) {
  *begin = n * static_cast<size_t>(w) / static_cast<size_t>(workers);
  *end = n * static_cast<size_t>(w + 1) / static_cast<size_t>(workers);
}

}  // namespace alignset

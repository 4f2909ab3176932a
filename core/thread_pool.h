#pragma once

#include <condition_variable>
#include <cstddef>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace alignset {

// A fixed set of worker threads for data-parallel loops. The engines own one
// each so that the thread count an optimization runs with is exactly what was
// configured (several optimizations side by side do not oversubscribe).
class ThreadPool {
 public:
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

  std::vector<std::thread> workers_;
  std::mutex mu_;
  std::condition_variable start_cv_;
  std::condition_variable done_cv_;
  const std::function<void(size_t, size_t, int)>* job_ = nullptr;
  size_t job_n_ = 0;
  size_t generation_ = 0;
  int pending_ = 0;
  bool stop_ = false;
};

// Chunk [begin, end) of worker `w` out of `workers` for a loop of n items.
inline void ChunkBounds(size_t n, int w, int workers, size_t* begin, size_t* end) {
  *begin = n * static_cast<size_t>(w) / static_cast<size_t>(workers);
  *end = n * static_cast<size_t>(w + 1) / static_cast<size_t>(workers);
}

}  // namespace alignset

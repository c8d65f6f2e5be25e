#pragma once
// A fixed pool of threads that runs one function over indices 0..n-1 and waits for all of them.
// Index i always runs on the same thread (i mod threads), so per-index work never migrates and
// results do not depend on scheduling. The calling thread does the share of thread 0.
#include <condition_variable>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace mimic {

class WorkerPool {
 public:
  explicit WorkerPool(int threads);  // threads >= 1
  ~WorkerPool();
  WorkerPool(const WorkerPool&) = delete;
  WorkerPool& operator=(const WorkerPool&) = delete;

  int threads() const { return threads_; }
  // Calls fn(i) for every i in [0, n); rethrows the first exception any call threw.
  void run(int n, const std::function<void(int)>& fn);

 private:
  void work(int thread_index);
  void run_share(int thread_index);

  int threads_;
  std::vector<std::thread> workers_;
  std::mutex mutex_;
  std::condition_variable start_, done_;
  const std::function<void(int)>* job_ = nullptr;
  int n_ = 0;
  long generation_ = 0;
  int pending_ = 0;
  bool quit_ = false;
  std::exception_ptr error_;
};

}  // namespace mimic

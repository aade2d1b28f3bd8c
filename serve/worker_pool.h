// A fixed number of threads running generation work off the HTTP threads, with a bounded
// queue: a request that finds the queue full is refused (503) instead of piling up.
#pragma once

#include <condition_variable>
#include <cstddef>
#include <deque>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace strand::serve {

class WorkerPool {
 public:
  // `threads` workers (at least 1); at most `max_waiting` tasks wait for a worker.
  WorkerPool(int threads, std::size_t max_waiting);
  ~WorkerPool();  // finishes the running tasks, drops the waiting ones
  WorkerPool(const WorkerPool&) = delete;
  WorkerPool& operator=(const WorkerPool&) = delete;

  // False when the queue is full (the task is not run).
  bool submit(std::function<void()> task);

 private:
  void work();
  std::mutex mu_;
  std::condition_variable cv_;
  std::deque<std::function<void()>> waiting_;
  std::size_t max_waiting_;
  bool stopping_ = false;
  std::vector<std::thread> threads_;
};

}  // namespace strand::serve

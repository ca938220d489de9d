// A small worker pool for the frame scheduler. `threads` counts the calling thread: a pool of N
// has N-1 workers and the caller joins in through help_until(); a pool of 1 has no workers and
// everything runs inline on the caller.
#pragma once

#include <condition_variable>
#include <deque>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace lantern {

class ThreadPool {
 public:
  explicit ThreadPool(unsigned threads);
  ~ThreadPool();
  ThreadPool(const ThreadPool&) = delete;
  ThreadPool& operator=(const ThreadPool&) = delete;

  unsigned threads() const { return static_cast<unsigned>(workers_.size()) + 1; }

  // Queues a task; callable from any thread, including from inside a running task.
  void submit(std::function<void()> task);
  // Runs queued tasks on the calling thread until `done()` holds. `done` is re-checked under
  // the pool's lock after every task completes, wherever it ran.
  void help_until(const std::function<bool()>& done);

 private:
  void worker_loop();
  void run_and_notify(std::function<void()>& task);

  std::mutex mutex_;
  std::condition_variable wake_;
  std::deque<std::function<void()>> queue_;
  bool stopping_ = false;
  std::vector<std::thread> workers_;
};

}  // namespace lantern

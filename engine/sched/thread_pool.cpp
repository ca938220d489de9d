// Worker threads and the help-while-waiting loop (see thread_pool.h).
#include "engine/sched/thread_pool.h"

#include <fmt/format.h>

#include "engine/core/error.h"

namespace lantern {

ThreadPool::ThreadPool(unsigned threads) {
  if (threads == 0 || threads > 256) {
    throw InputError(fmt::format("thread pool: thread count must be 1..256, got {}", threads));
  }
  workers_.reserve(threads - 1);
  for (unsigned i = 1; i < threads; ++i) workers_.emplace_back([this] { worker_loop(); });
}

ThreadPool::~ThreadPool() {
  {
    std::lock_guard lock(mutex_);
    stopping_ = true;
  }
  wake_.notify_all();
  for (std::thread& t : workers_) t.join();
}

void ThreadPool::submit(std::function<void()> task) {
  {
    std::lock_guard lock(mutex_);
    queue_.push_back(std::move(task));
  }
  wake_.notify_all();
}

// Tasks must not throw (the scheduler catches inside its tasks); the notify under the lock makes
// a waiter that just checked `done` see the completion.
void ThreadPool::run_and_notify(std::function<void()>& task) {
  task();
  std::lock_guard lock(mutex_);
  wake_.notify_all();
}

void ThreadPool::worker_loop() {
  std::unique_lock lock(mutex_);
  for (;;) {
    wake_.wait(lock, [this] { return stopping_ || !queue_.empty(); });
    if (stopping_ && queue_.empty()) return;
    std::function<void()> task = std::move(queue_.front());
    queue_.pop_front();
    lock.unlock();
    run_and_notify(task);
    lock.lock();
  }
}

void ThreadPool::help_until(const std::function<bool()>& done) {
  std::unique_lock lock(mutex_);
  while (!done()) {
    if (queue_.empty()) {
      wake_.wait(lock);
      continue;
    }
    std::function<void()> task = std::move(queue_.front());
    queue_.pop_front();
    lock.unlock();
    run_and_notify(task);
    lock.lock();
  }
}

}  // namespace lantern

#include "app/worker_pool.hpp"

#include "app/thread_priority.hpp"

namespace rrlab::server {

WorkerPool::WorkerPool(int threads, int nice_steps, std::size_t max_queued) : max_queued_(max_queued) {
  for (int i = 0; i < threads; ++i) workers_.emplace_back([this, nice_steps] { work(nice_steps); });
}

WorkerPool::~WorkerPool() { stop(); }

bool WorkerPool::stopping() {
  std::lock_guard lock(mutex_);
  return stopping_;
}

bool WorkerPool::post(std::function<void()> task) {
  {
    std::lock_guard lock(mutex_);
    if (stopping_ || (max_queued_ > 0 && tasks_.size() >= max_queued_)) return false;
    tasks_.push_back(std::move(task));
  }
  wake_.notify_one();
  return true;
}

void WorkerPool::stop() {
  std::deque<std::function<void()>> dropped;  // destroyed outside the lock (they may hold reservations)
  {
    std::lock_guard lock(mutex_);
    stopping_ = true;
    dropped.swap(tasks_);
  }
  wake_.notify_all();
  for (auto& worker : workers_) {
    if (!worker.joinable()) continue;
    // the last owner of the pool may be a task on a worker: never join oneself
    if (worker.get_id() == std::this_thread::get_id())
      worker.detach();
    else
      worker.join();
  }
}

void WorkerPool::work(int nice_steps) {
  if (nice_steps > 0) lower_thread_priority(nice_steps);
  for (;;) {
    std::function<void()> task;
    {
      std::unique_lock lock(mutex_);
      wake_.wait(lock, [&] { return stopping_ || !tasks_.empty(); });
      if (stopping_) return;
      task = std::move(tasks_.front());
      tasks_.pop_front();
    }
    try {
      task();
    } catch (...) {
      // a task reports its own failures; nothing may end a worker
    }
  }
}

}  // namespace rrlab::server

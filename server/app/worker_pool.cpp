#include <rrlab/server/app/worker_pool.hpp>

#include <algorithm>

#include <rrlab/server/app/thread_priority.hpp>

namespace rrlab::server {

WorkerPool::WorkerPool(int threads, int nice_steps, std::size_t max_queued)
    : max_queued_(max_queued), max_per_owner_(max_queued == 0 ? 0 : std::max<std::size_t>(1, max_queued / 4)) {
  for (int i = 0; i < threads; ++i) workers_.emplace_back([this, nice_steps] { work(nice_steps); });
}

WorkerPool::~WorkerPool() { stop(); }

bool WorkerPool::stopping() {
  std::lock_guard lock(mutex_);
  return stopping_;
}

bool WorkerPool::post(std::function<void()> task, const std::string& owner) {
  {
    std::lock_guard lock(mutex_);
    if (stopping_ || (max_queued_ > 0 && queued_ >= max_queued_)) return false;
    std::deque<std::function<void()>>& queue = queues_[owner];
    if (max_per_owner_ > 0 && queue.size() >= max_per_owner_) return false;
    if (queue.empty()) turns_.push_back(owner);
    queue.push_back(std::move(task));
    ++queued_;
  }
  wake_.notify_one();
  return true;
}

void WorkerPool::stop() {
  std::map<std::string, std::deque<std::function<void()>>> dropped;  // destroyed outside the lock (they may hold reservations)
  {
    std::lock_guard lock(mutex_);
    stopping_ = true;
    dropped.swap(queues_);
    turns_.clear();
    queued_ = 0;
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
      wake_.wait(lock, [&] { return stopping_ || !turns_.empty(); });
      if (stopping_) return;
      // the owner whose turn it is gives its oldest task, and goes to the back
      const std::string owner = std::move(turns_.front());
      turns_.pop_front();
      auto queue = queues_.find(owner);
      task = std::move(queue->second.front());
      queue->second.pop_front();
      --queued_;
      if (queue->second.empty())
        queues_.erase(queue);
      else
        turns_.push_back(owner);
    }
    try {
      task();
    } catch (...) {
      // a task reports its own failures; nothing may end a worker
    }
  }
}

}  // namespace rrlab::server

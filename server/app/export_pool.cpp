#include "app/export_pool.hpp"

#include "app/thread_priority.hpp"

namespace rrlab::server {

ExportPool::ExportPool(int threads, std::size_t budget) : budget_(budget) {
  for (int i = 0; i < threads; ++i) workers_.emplace_back([this] { work(); });
}

ExportPool::~ExportPool() { stop(); }

bool ExportPool::stopping() {
  std::lock_guard lock(mutex_);
  return stopping_;
}

std::shared_ptr<ExportPool::Ticket> ExportPool::reserve(std::size_t bytes) {
  {
    std::lock_guard lock(mutex_);
    if (reserved_ + bytes > budget_) return nullptr;
    reserved_ += bytes;
  }
  return std::make_shared<Ticket>(*this, bytes);
}

void ExportPool::release(std::size_t bytes) {
  std::lock_guard lock(mutex_);
  reserved_ -= bytes;
}

std::size_t ExportPool::reserved() const {
  std::lock_guard lock(mutex_);
  return reserved_;
}

void ExportPool::post(std::function<void()> task) {
  {
    std::lock_guard lock(mutex_);
    if (stopping_) return;
    tasks_.push_back(std::move(task));
  }
  wake_.notify_one();
}

void ExportPool::stop() {
  std::deque<std::function<void()>> dropped;  // destroyed outside the lock (they may hold tickets)
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

void ExportPool::work() {
  lower_thread_priority(5);  // exports are bulk work: below the I/O threads and the live runs
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

// A few worker threads with a queue: work that must not run on the I/O
// threads (scenario building, frame exports). Tasks run in the order posted.
#pragma once

#include <condition_variable>
#include <cstddef>
#include <deque>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace rrlab::server {

class WorkerPool {
 public:
  // `threads` workers, `nice_steps` below the priority of the thread that
  // makes the pool (app/thread_priority.hpp); at most `max_queued` tasks
  // waiting (0: no bound).
  WorkerPool(int threads, int nice_steps, std::size_t max_queued = 0);
  ~WorkerPool();  // stop()
  WorkerPool(const WorkerPool&) = delete;
  WorkerPool& operator=(const WorkerPool&) = delete;

  // Queues `task`; false when it is dropped (the pool stopped, or its queue is full).
  bool post(std::function<void()> task);
  // Drops queued tasks and joins the workers (a task under way finishes first).
  void stop();
  bool stopping();  // stop() has begun

 private:
  void work(int nice_steps);

  const std::size_t max_queued_;
  std::mutex mutex_;
  std::condition_variable wake_;
  std::deque<std::function<void()>> tasks_;
  bool stopping_ = false;
  std::vector<std::thread> workers_;
};

}  // namespace rrlab::server

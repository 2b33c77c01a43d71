// A few worker threads with a queue: work that must not run on the I/O
// threads (scenario building, frame exports, sweep reports). Fair between
// owners (a client's address): each owner has its own queue and the workers
// take the owners' oldest tasks in turn, so one client's burst of slow
// requests delays another's by at most one task each, never by the burst.
#pragma once

#include <condition_variable>
#include <cstddef>
#include <deque>
#include <functional>
#include <map>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

namespace rrlab::server {

class WorkerPool {
 public:
  // `threads` workers, `nice_steps` below the priority of the thread that
  // makes the pool (app/thread_priority.hpp); at most `max_queued` tasks
  // waiting in all (0: no bound), and at most a quarter of that (at least
  // one) from one owner.
  WorkerPool(int threads, int nice_steps, std::size_t max_queued = 0);
  ~WorkerPool();  // stop()
  WorkerPool(const WorkerPool&) = delete;
  WorkerPool& operator=(const WorkerPool&) = delete;

  // Queues `task` for `owner`; false when it is dropped (the pool stopped,
  // its queue is full, or the owner's share of it is).
  bool post(std::function<void()> task, const std::string& owner = "");
  // Drops queued tasks and joins the workers (a task under way finishes first).
  void stop();
  bool stopping();  // stop() has begun

 private:
  void work(int nice_steps);

  const std::size_t max_queued_, max_per_owner_;
  std::mutex mutex_;
  std::condition_variable wake_;
  std::map<std::string, std::deque<std::function<void()>>> queues_;  // by owner; none empty
  std::deque<std::string> turns_;  // owners with queued tasks, the next to be served first
  std::size_t queued_ = 0;
  bool stopping_ = false;
  std::vector<std::thread> workers_;
};

}  // namespace rrlab::server

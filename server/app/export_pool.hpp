// Where streamed answers (frame exports) are produced: a few worker threads,
// never the I/O threads, and a budget of bytes in flight shared by every
// connection. Each export reserves what it may hold at once (one chunk) when
// it starts; an export that would go over the budget is refused (the caller
// answers 503 with Retry-After). A connection produces its next chunk only
// after the previous one was written, so a client that does not read holds
// one chunk and nothing more.
#pragma once

#include <cstddef>
#include <functional>
#include <memory>
#include <mutex>

#include <rrlab/server/app/worker_pool.hpp>

namespace rrlab::server {

class ExportPool {
 public:
  // `threads` workers (below the I/O threads' priority); `budget` bytes that
  // all exports together may reserve.
  ExportPool(int threads, std::size_t budget) : budget_(budget), workers_(threads, 5) {}
  ExportPool(const ExportPool&) = delete;
  ExportPool& operator=(const ExportPool&) = delete;

  // Bytes reserved by one export until it ends: released when the last copy
  // of the ticket goes away (a completed export, or a closed connection).
  class Ticket {
   public:
    Ticket(ExportPool& pool, std::size_t bytes) : pool_(pool), bytes_(bytes) {}
    ~Ticket() { pool_.release(bytes_); }
    Ticket(const Ticket&) = delete;
    Ticket& operator=(const Ticket&) = delete;

   private:
    ExportPool& pool_;
    std::size_t bytes_;
  };

  // A reservation of `bytes`, or null when it would take the reserved total
  // over the budget.
  std::shared_ptr<Ticket> reserve(std::size_t bytes);
  std::size_t reserved() const;
  std::size_t budget() const { return budget_; }

  // Runs `task` on a worker (tasks run in the order posted). After stop(),
  // tasks are dropped.
  void post(std::function<void()> task) { workers_.post(std::move(task)); }

  // Drops queued tasks and joins the workers (a task under way finishes
  // first). Called before the run store goes away.
  void stop() { workers_.stop(); }
  bool stopping() { return workers_.stopping(); }  // stop() has begun

 private:
  void release(std::size_t bytes);

  const std::size_t budget_;
  mutable std::mutex mutex_;
  std::size_t reserved_ = 0;
  WorkerPool workers_;  // last: stopped (joined) before the budget goes
};

}  // namespace rrlab::server

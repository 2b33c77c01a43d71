#include <rrlab/storage/frame_writer.hpp>

#include <vector>

#include <rrlab/storage/database.hpp>

namespace rrlab::storage {

FrameWriter::FrameWriter(RunStore& store, size_t capacity, size_t batch)
    : store_(store), capacity_(capacity), batch_(batch), thread_([this] { loop(); }) {}

FrameWriter::~FrameWriter() {
  {
    std::lock_guard lock(mutex_);
    stopping_ = true;
  }
  not_empty_.notify_all();
  thread_.join();
}

void FrameWriter::push(std::int64_t run, StoredFrame&& frame) {
  std::unique_lock lock(mutex_);
  not_full_.wait(lock, [&] { return queued_frames_ < capacity_; });
  queued_bytes_ += std::int64_t(frame.data.size());
  queue_.push_back({run, std::move(frame), std::nullopt, nullptr});
  ++queued_frames_;
  ++pushed_;
  if (queue_.size() == 1 || queue_.size() >= batch_) not_empty_.notify_one();
}

void FrameWriter::push_event(std::int64_t run, StoredEvent&& event, std::shared_ptr<Completion> committed) {
  {
    std::lock_guard lock(mutex_);
    queue_.push_back({run, {}, std::move(event), std::move(committed)});
    ++pushed_;
  }
  not_empty_.notify_one();  // someone may wait on it: written without waiting for a batch to fill
}

void FrameWriter::flush() {
  std::unique_lock lock(mutex_);
  const std::uint64_t target = pushed_;
  not_empty_.notify_one();
  drained_.wait(lock, [&] { return committed_ >= target; });
}

std::string FrameWriter::last_error() {
  std::lock_guard lock(mutex_);
  return error_;
}

std::optional<std::string> FrameWriter::run_error(std::int64_t run) {
  std::lock_guard lock(mutex_);
  if (auto it = run_errors_.find(run); it != run_errors_.end()) return it->second.first;
  return std::nullopt;
}

void FrameWriter::loop() {
  std::vector<std::pair<std::int64_t, StoredFrame>> frames;
  std::vector<std::pair<std::int64_t, StoredEvent>> events;
  std::vector<std::shared_ptr<Completion>> completions;  // of the events written
  std::vector<std::pair<std::shared_ptr<Completion>, Outcome>> refused;  // events of failed runs
  size_t taken = 0;  // items taken off the queue, dropped ones included
  for (;;) {
    {
      std::unique_lock lock(mutex_);
      not_empty_.wait(lock, [&] { return stopping_ || !queue_.empty(); });
      if (queue_.empty()) return;  // stopping and drained
      frames.clear();
      events.clear();
      completions.clear();
      refused.clear();
      taken = 0;
      while (!queue_.empty() && taken < batch_) {
        ++taken;
        Queued& item = queue_.front();
        // a run whose writes failed before stores nothing later (no gaps)
        const auto failed = run_errors_.find(item.run);
        if (item.event) {
          if (failed == run_errors_.end()) {
            events.emplace_back(item.run, std::move(*item.event));
            completions.push_back(std::move(item.committed));
          } else if (item.committed) {
            refused.emplace_back(std::move(item.committed), Outcome{failed->second.first, failed->second.second, {}});
          }
        } else {
          --queued_frames_;
          if (failed == run_errors_.end()) frames.emplace_back(item.run, std::move(item.frame));
          else queued_bytes_ -= std::int64_t(item.frame.data.size());
        }
        queue_.pop_front();
      }
    }
    not_full_.notify_all();
    std::string error;
    StorageFault fault = StorageFault::other;
    try {
      store_.add_frames(frames, events);
    } catch (const StorageError& e) {
      error = e.what();
      fault = e.fault();
    } catch (const std::exception& e) {
      error = e.what();
    }
    std::int64_t bytes = 0;
    for (const auto& [run, frame] : frames) bytes += std::int64_t(frame.data.size());
    queued_bytes_ -= bytes;
    {
      std::lock_guard lock(mutex_);
      committed_ += taken;
      if (!error.empty()) {
        error_ = error;
        for (const auto& [run, frame] : frames)
          if (run_errors_.emplace(run, std::make_pair(error, fault)).second) ++failures_;
        for (const auto& [run, event] : events)
          if (run_errors_.emplace(run, std::make_pair(error, fault)).second) ++failures_;
      }
    }
    drained_.notify_all();
    // outside the lock: a callback may post a reply, or push again
    for (auto& [completion, outcome] : refused) completion->settle(std::move(outcome));
    for (auto& completion : completions)
      if (completion) completion->settle(Outcome{error, fault, {}});
  }
}

}  // namespace rrlab::storage

#include "storage/frame_writer.hpp"

#include <vector>

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
  not_full_.wait(lock, [&] { return queue_.size() < capacity_; });
  queued_bytes_ += std::int64_t(frame.data.size());
  queue_.emplace_back(run, std::move(frame));
  ++pushed_;
  if (queue_.size() == 1 || queue_.size() >= batch_) not_empty_.notify_one();
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
  if (auto it = run_errors_.find(run); it != run_errors_.end()) return it->second;
  return std::nullopt;
}

void FrameWriter::loop() {
  std::vector<std::pair<std::int64_t, StoredFrame>> batch;
  size_t taken = 0;  // frames taken off the queue, dropped ones included
  for (;;) {
    {
      std::unique_lock lock(mutex_);
      not_empty_.wait(lock, [&] { return stopping_ || !queue_.empty(); });
      if (queue_.empty()) return;  // stopping and drained
      batch.clear();
      taken = 0;
      while (!queue_.empty() && taken < batch_) {
        ++taken;
        // a run whose frames failed before stores no later ones (no gaps)
        if (!run_errors_.count(queue_.front().first)) batch.push_back(std::move(queue_.front()));
        else queued_bytes_ -= std::int64_t(queue_.front().second.data.size());
        queue_.pop_front();
      }
    }
    not_full_.notify_all();
    std::string error;
    try {
      store_.add_frames(batch);
    } catch (const std::exception& e) {
      error = e.what();
    }
    std::int64_t bytes = 0;
    for (const auto& [run, frame] : batch) bytes += std::int64_t(frame.data.size());
    queued_bytes_ -= bytes;
    {
      std::lock_guard lock(mutex_);
      committed_ += taken;
      if (!error.empty()) {
        error_ = error;
        for (const auto& [run, frame] : batch)
          if (run_errors_.emplace(run, error).second) ++failures_;
      }
    }
    drained_.notify_all();
  }
}

}  // namespace rrlab::storage

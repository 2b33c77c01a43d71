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

void FrameWriter::loop() {
  std::vector<std::pair<std::int64_t, StoredFrame>> batch;
  for (;;) {
    {
      std::unique_lock lock(mutex_);
      not_empty_.wait(lock, [&] { return stopping_ || !queue_.empty(); });
      if (queue_.empty()) return;  // stopping and drained
      batch.clear();
      while (!queue_.empty() && batch.size() < batch_) {
        batch.push_back(std::move(queue_.front()));
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
    {
      std::lock_guard lock(mutex_);
      committed_ += batch.size();
      if (!error.empty()) error_ = error;
    }
    drained_.notify_all();
  }
}

}  // namespace rrlab::storage

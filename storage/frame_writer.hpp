// Writes frames off the simulation thread: a bounded queue drained by one
// thread in batched transactions. A full queue makes push() wait (storage
// back-pressure slows a run down rather than dropping its frames).
#pragma once

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <map>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <utility>

#include "storage/run_store.hpp"

namespace rrlab::storage {

class FrameWriter {
 public:
  explicit FrameWriter(RunStore& store, size_t capacity = 16384, size_t batch = 1024);
  ~FrameWriter();  // writes what is queued, then stops
  FrameWriter(const FrameWriter&) = delete;
  FrameWriter& operator=(const FrameWriter&) = delete;

  void push(std::int64_t run, StoredFrame&& frame);
  // Returns once every frame pushed before the call is committed.
  void flush();
  // The last write error ("" if none); frames of a failed batch are lost.
  std::string last_error();
  // The error of the first failed batch holding a frame of `run`, if any.
  // Later frames of that run are dropped (not written): its stored frames
  // stay a gap-free prefix. Bumps failures() when a run first fails.
  std::optional<std::string> run_error(std::int64_t run);
  std::uint64_t failures() const { return failures_; }
  // Bytes of frame data pushed and not yet committed (or dropped).
  std::int64_t queued_bytes() const { return queued_bytes_; }

 private:
  void loop();

  RunStore& store_;
  const size_t capacity_, batch_;
  std::mutex mutex_;
  std::condition_variable not_empty_, not_full_, drained_;
  std::deque<std::pair<std::int64_t, StoredFrame>> queue_;
  std::uint64_t pushed_ = 0, committed_ = 0;
  bool stopping_ = false;
  std::string error_;
  std::map<std::int64_t, std::string> run_errors_;  // runs whose frames failed to be written
  std::atomic<std::uint64_t> failures_{0};
  std::atomic<std::int64_t> queued_bytes_{0};
  std::thread thread_;
};

}  // namespace rrlab::storage

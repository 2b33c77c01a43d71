// Writes frames off the simulation thread: a bounded queue drained by one
// thread in batched transactions. A full queue makes push() wait (storage
// back-pressure slows a run down rather than dropping its frames).
#pragma once

#include <condition_variable>
#include <cstdint>
#include <deque>
#include <mutex>
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
  std::thread thread_;
};

}  // namespace rrlab::storage

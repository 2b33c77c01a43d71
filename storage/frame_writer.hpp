// Writes frames and input events off the simulation and I/O threads: one
// queue drained by one thread in batched transactions, in the order pushed
// (an input's event is queued before the frames it takes effect in, so it is
// committed with them or before). Frames fill a bounded queue, and a full
// queue makes push() wait (storage back-pressure slows a run down rather than
// dropping its frames); events never wait, and their Completion settles once
// they are committed: who acknowledges an input waits on that, not on SQLite.
#pragma once

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <utility>

#include <rrlab/storage/completion.hpp>
#include <rrlab/storage/run_store.hpp>

namespace rrlab::storage {

class FrameWriter {
 public:
  explicit FrameWriter(RunStore& store, size_t capacity = 16384, size_t batch = 1024);
  ~FrameWriter();  // writes what is queued, then stops
  FrameWriter(const FrameWriter&) = delete;
  FrameWriter& operator=(const FrameWriter&) = delete;

  void push(std::int64_t run, StoredFrame&& frame);
  // Never waits; `committed` (if any) settles once the event is committed,
  // or with the error that kept it out (the run's frames or events failed).
  void push_event(std::int64_t run, StoredEvent&& event, std::shared_ptr<Completion> committed = nullptr);
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
  struct Queued {
    std::int64_t run = 0;
    StoredFrame frame;
    std::optional<StoredEvent> event;  // set: an event, not a frame
    std::shared_ptr<Completion> committed;
  };
  void loop();

  RunStore& store_;
  const size_t capacity_, batch_;
  std::mutex mutex_;
  std::condition_variable not_empty_, not_full_, drained_;
  std::deque<Queued> queue_;
  size_t queued_frames_ = 0;  // against capacity_ (events do not count)
  std::uint64_t pushed_ = 0, committed_ = 0;
  bool stopping_ = false;
  std::string error_;
  std::map<std::int64_t, std::pair<std::string, StorageFault>> run_errors_;  // runs whose writes failed
  std::atomic<std::uint64_t> failures_{0};
  std::atomic<std::int64_t> queued_bytes_{0};
  std::thread thread_;
};

}  // namespace rrlab::storage

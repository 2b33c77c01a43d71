// Frame bytes against `serve --max-total-bytes`: what the store holds
// (RunStore::total_frame_bytes), what the writer has queued, and what admitted
// runs may still store (their estimates, reserved at admission and released
// as their frames are pushed or when they end).
#pragma once

#include <atomic>
#include <cstdint>

namespace rrlab::storage {
class RunStore;
class FrameWriter;
}  // namespace rrlab::storage

namespace rrlab::server {

class StorageBudget {
 public:
  StorageBudget(storage::RunStore& store, storage::FrameWriter& writer, std::int64_t max_total_bytes)
      : store_(store), writer_(writer), max_(max_total_bytes) {}
  std::int64_t max() const { return max_; }
  std::int64_t stored() const;  // in the store or queued for it
  std::int64_t reserved() const { return reserved_; }
  std::int64_t used() const { return stored() + reserved(); }
  void reserve(std::int64_t bytes) { reserved_ += bytes; }
  void release(std::int64_t bytes) { reserved_ -= bytes; }
  // A frame beyond its run's reservation: true if it fits under the maximum.
  bool fits(std::int64_t bytes) const { return used() + bytes <= max_; }

 private:
  storage::RunStore& store_;
  storage::FrameWriter& writer_;
  const std::int64_t max_;
  std::atomic<std::int64_t> reserved_{0};
};

}  // namespace rrlab::server

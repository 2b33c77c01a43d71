// A run's stored frames from..to at a stride, read a batch at a time, each
// batch from its own short query: a streamed export (frames, drawn frames)
// holds no SQLite statement or lock while it encodes or the client reads.
#pragma once

#include <cstdint>
#include <vector>

#include <rrlab/storage/run_store.hpp>

namespace rrlab::server {

class FrameBatches {
 public:
  FrameBatches(storage::RunStore& store, std::int64_t run, std::int64_t from, std::int64_t to, std::int64_t stride)
      : store_(store), run_(run), next_(from), to_(to), stride_(stride) {}

  // The next batch of at most `rows` frames, in seq order (empty once done).
  const std::vector<storage::StoredFrame>& next(std::size_t rows);
  bool done() const { return next_ > to_; }
  // Once done: throws DomainError not_found when the run was deleted meanwhile
  // (DELETE takes a stored run at any time): its frames stopped short, so a
  // body must not end as if complete.
  void check_complete() const;

 private:
  storage::RunStore& store_;
  const std::int64_t run_;
  std::int64_t next_;  // the next seq to read
  const std::int64_t to_, stride_;
  std::vector<storage::StoredFrame> batch_;
};

}  // namespace rrlab::server

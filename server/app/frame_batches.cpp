#include <rrlab/server/app/frame_batches.hpp>

#include <string>

#include <rrlab/server/api/errors.hpp>

namespace rrlab::server {

const std::vector<storage::StoredFrame>& FrameBatches::next(std::size_t rows) {
  batch_.clear();
  if (done() || rows == 0) return batch_;
  store_.frames(run_, next_, to_, stride_, [&](const storage::StoredFrame& f) {
    batch_.push_back(f);
    return batch_.size() < rows;
  });
  // the rows keep their alignment: seq - from is a multiple of stride
  next_ = batch_.size() < rows ? to_ + 1 : batch_.back().seq + stride_;
  return batch_;
}

void FrameBatches::check_complete() const {
  if (!store_.run(run_))
    throw DomainError(Problem::not_found, "not_found", "run " + std::to_string(run_) + " was deleted", "id");
}

}  // namespace rrlab::server

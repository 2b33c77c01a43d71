#include <rrlab/server/app/storage_budget.hpp>

#include <rrlab/storage/frame_writer.hpp>
#include <rrlab/storage/run_store.hpp>

namespace rrlab::server {

std::int64_t StorageBudget::stored() const { return store_.total_frame_bytes() + writer_.queued_bytes(); }

}  // namespace rrlab::server

// Admission: what a request may start, weighed before anything is stored.
// Runs, re-simulations and sweeps are checked against the per-run limits
// (frames, bytes: too_large "run_too_large"), their summed cost estimate
// (too_large) and the total frame bytes of the database (quota
// "storage_quota"), and reserve their estimated bytes of the total
// (StorageBudget). The error names the limit ("limit") and the numbers
// ("requested", "allowed", and what is stored).
#pragma once

#include <cstdint>
#include <mutex>
#include <vector>

#include <rrlab/server/app/lane_estimate.hpp>
#include <rrlab/server/app/storage_budget.hpp>
#include <rrlab/storage/quotas.hpp>

namespace rrlab::storage {
class RunStore;
class FrameWriter;
}  // namespace rrlab::storage

namespace rrlab::server {

class Admission {
 public:
  Admission(storage::RunStore& store, storage::FrameWriter& writer, const Quotas& quotas);

  StorageBudget& budget() { return budget_; }

  // storage_full / storage_readonly while a write fault lasts (a probe write
  // decides whether it still does): no new work is started meanwhile.
  void check_writable();

  // Admissions one at a time: held by whoever admits (a run group's start
  // holds it from its checks until the group is registered), so that the
  // limits hold under concurrent requests.
  std::unique_lock<std::mutex> hold() { return std::unique_lock(mutex_); }
  // Checks `lanes` and reserves their frame bytes; returns each lane's
  // reservation. `frames` false: they store summaries only (no per-run frame
  // limits apply). `window` > 0: each lane reserves at most that many bytes (a
  // live lane's window ahead). The caller holds hold().
  std::vector<std::int64_t> admit_held(const std::vector<LaneEstimate>& lanes, bool frames, std::int64_t window = 0);
  // Work that is not a run group (a re-simulation, a sweep): admitted as
  // above (taking hold() itself); returns the bytes it reserved, for
  // release() as its frames are stored.
  std::int64_t admit_work(const std::vector<LaneEstimate>& lanes, bool frames);
  void release(std::int64_t bytes) { budget_.release(bytes); }

 private:
  storage::RunStore& store_;
  const Quotas quotas_;
  StorageBudget budget_;
  std::mutex mutex_;
};

}  // namespace rrlab::server

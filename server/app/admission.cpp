#include <rrlab/server/app/admission.hpp>

#include <algorithm>
#include <cstdio>
#include <string>

#include <rrlab/server/api/errors.hpp>
#include <rrlab/storage/database.hpp>
#include <rrlab/storage/run_store.hpp>

namespace rrlab::server {

namespace {
std::string mib(std::int64_t bytes) {
  char text[32];
  std::snprintf(text, sizeof text, "%.1f MiB", double(bytes) / double(1 << 20));
  return text;
}
}  // namespace

Admission::Admission(storage::RunStore& store, storage::FrameWriter& writer, const Quotas& quotas)
    : store_(store), quotas_(quotas), budget_(store, writer, quotas.max_total_bytes) {}

void Admission::check_writable() {
  if (!store_.write_fault() || store_.probe_write()) return;
  const auto fault = store_.write_fault();
  if (!fault) return;
  const bool full = fault->fault == storage::StorageFault::full;
  throw DomainError(full ? Problem::storage_full : Problem::storage_readonly, full ? "storage_full" : "storage_readonly",
                    std::string(full ? "the database's disk is full" : "the database cannot be written") + " (" +
                        fault->message + "): no new run is started until " +
                        (full ? "space is freed (delete runs, or free the disk)" : "the file is writable again") +
                        "; stored runs can still be read");
}

std::int64_t Admission::admit_work(const std::vector<LaneEstimate>& lanes, bool frames) {
  auto held = hold();
  std::int64_t total = 0;
  for (const std::int64_t bytes : admit_held(lanes, frames)) total += bytes;
  return total;
}

std::vector<std::int64_t> Admission::admit_held(const std::vector<LaneEstimate>& lanes, bool frames,
                                                std::int64_t window) {
  double cost = 0;
  std::int64_t bytes = 0;
  std::vector<std::int64_t> reserve;
  for (const LaneEstimate& lane : lanes) {
    cost += run_cost(lane);
    if (!frames) continue;
    if (lane.steps > quotas_.max_run_frames)
      throw DomainError(Problem::too_large, "run_too_large",
                        "max_run_frames: " + std::to_string(lane.steps) + " steps would store " +
                            std::to_string(lane.steps) + " frames; a run may store at most " +
                            std::to_string(quotas_.max_run_frames) + " (serve --max-run-frames): ask for fewer steps",
                        "steps",
                        {{"limit", "max_run_frames"}, {"requested", lane.steps}, {"allowed", quotas_.max_run_frames}});
    const std::int64_t lane_bytes = lane.steps * lane.frame_bytes;
    if (lane_bytes > quotas_.max_run_bytes)
      throw DomainError(Problem::too_large, "run_too_large",
                        "max_run_bytes: " + std::to_string(lane.steps) + " frames of " +
                            std::to_string(lane.frame_bytes) + " bytes (" + std::to_string(lane.dof) + " joints) are " +
                            std::to_string(lane_bytes) + " bytes (" + mib(lane_bytes) + "); a run may store at most " +
                            std::to_string(quotas_.max_run_bytes) + " (" + mib(quotas_.max_run_bytes) +
                            ", serve --max-run-bytes): ask for fewer steps",
                        "steps",
                        {{"limit", "max_run_bytes"}, {"requested", lane_bytes}, {"allowed", quotas_.max_run_bytes},
                         {"frames", lane.steps}, {"frame_bytes", lane.frame_bytes}});
    const std::int64_t reserved = window > 0 ? std::min(lane_bytes, window) : lane_bytes;
    bytes += reserved;
    reserve.push_back(reserved);
  }
  if (cost > quotas_.max_run_cost) {
    char text[64];
    std::snprintf(text, sizeof text, "%.6g", cost);
    std::string message = "max_run_cost: the estimate DOF x (obstacles + 1) x steps x method factor";
    const auto number = [](double v) {
      char out[32];
      std::snprintf(out, sizeof out, "%.4g", v);
      return std::string(out);
    };
    if (lanes.size() > 8) message += ", summed over " + std::to_string(lanes.size()) + " runs,";
    else
      for (const LaneEstimate& lane : lanes)
        message += (&lane == &lanes.front() ? " = " : " + ") + std::to_string(lane.dof) + " x (" +
                   number(lane.obstacles) + " + 1) x " + std::to_string(lane.steps) + " x " + number(lane.factor);
    char allowed[64];
    std::snprintf(allowed, sizeof allowed, "%.6g", quotas_.max_run_cost);
    throw DomainError(Problem::too_large, "run_too_large",
                      message + " = " + text + " exceeds " + allowed + " (serve --max-run-cost): ask for fewer steps",
                      "steps", {{"limit", "max_run_cost"}, {"requested", cost}, {"allowed", quotas_.max_run_cost}});
  }
  const std::int64_t used = budget_.used();
  if (used + bytes > budget_.max())
    throw DomainError(Problem::quota, "storage_quota",
                      "max_total_bytes: the runs would reserve " + std::to_string(bytes) + " bytes of frames (" +
                          mib(bytes) + ") and the database holds " + std::to_string(used) + " (" + mib(used) +
                          ", stored, queued or reserved by running runs) of at most " + std::to_string(budget_.max()) +
                          " (" + mib(budget_.max()) + ", serve --max-total-bytes): delete runs or ask for fewer steps",
                      "",
                      {{"limit", "max_total_bytes"}, {"requested", bytes}, {"stored", used}, {"allowed", budget_.max()}});
  budget_.reserve(bytes);
  return reserve;
}

}  // namespace rrlab::server

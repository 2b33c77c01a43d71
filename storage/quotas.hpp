// The quota defaults, in one place: `rrlab serve` takes each as an option
// (cli/), the run manager and run groups enforce them (server/app/), sweeps
// store no more frames per run than a server would (sweep/). A request beyond
// a per-run quota is 413 "run_too_large", beyond a total 507 "storage_quota"
// (docs/api.md, "Quotas").
#pragma once

#include <cstdint>

namespace rrlab {

struct Quotas {
  int max_active_runs = 256;       // unfinished runs at once (503 beyond)
  int max_kept_finished = 64;      // finished groups kept in memory for their WebSocket clients
  int max_replays = 32;            // at once; beyond, the oldest unwatched one ends (503 if every one is watched)
  int max_replays_per_client = 8;  // per client name, or per address for requests without one
  long max_run_frames = 1'000'000;           // --max-run-frames: frames one run may store
  std::int64_t max_run_bytes = 256ll << 20;  // --max-run-bytes: frame bytes one run may store
  std::int64_t max_total_bytes = 8ll << 30;  // --max-total-bytes: frame bytes of every run in the database
  // --max-run-cost: DOF x (obstacles + 1) x steps x the method's factor,
  // summed over a request's runs. 2e10 is about ten minutes of one core (a
  // 64-joint, 256-obstacle, 1e7-step run is 1.6e11, about 80 minutes).
  double max_run_cost = 2e10;
  std::int64_t max_scenarios = 1000;  // --max-scenarios: scenarios stored over REST
  // Live runs (server only): an address holds at most this many live runs or
  // compare groups (a group counts once; client names share their address's
  // count); a new one beyond ends the address's oldest unwatched one, or is
  // refused (429) when every one is watched. --max-live-per-address
  int max_live_per_address = 16;
  // A live lane reserves of --max-total-bytes at most this many bytes of what
  // it will store, not its whole duration's frames, so that runs that store
  // nothing never fill the quota; its frames past the reservation are stored
  // while the total still fits (else it stops storing, storage_stopped).
  // --live-reserve-bytes
  std::int64_t live_reserve_bytes = 16ll << 20;
  // A live run with no WebSocket client and no REST call for it for this long
  // after its start ends as abandoned (stored frames kept). --abandon-unwatched-s
  int abandon_unwatched_s = 30;
  // ... and later on, with no viewer and no input for this long. --abandon-idle-s
  int abandon_idle_s = 600;
};

}  // namespace rrlab

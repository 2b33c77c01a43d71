#include <filesystem>
#include <iostream>

#include <rrlab/storage/resimulation.hpp>
#include <rrlab/storage/run_store.hpp>

#include "cli.hpp"

namespace rrlab::cli {

namespace {
// --verify's exit codes: 0 identical, 1 a frame (or a frameless run's summary)
// differs, 2 bad input, 3 the run stored nothing to compare (no frames, no steps).
constexpr int kExitNothingCompared = 3;
}  // namespace

// Re-simulates a stored run and prints {run, frames_compared, identical, ...}.
int replay(const ReplayOptions& options) {
  try {
    if (!database_exists(options.db)) return 2;
    storage::RunStore store(options.db);
    const auto run = store.run(options.run_id);
    if (!run) {
      std::cerr << "rrlab: error: no run " << options.run_id << " in " << options.db << '\n';
      return 2;
    }
    const storage::ResimulationResult result = storage::resimulate(store, *run, {});
    nlohmann::json out = {{"run", run->id}, {"frames_stored", run->frames}};
    out.update(storage::verification_json(result));
    out["summary"] = summary_to_json(result.summary);
    std::cout << out.dump() << '\n';
    if (!result.compared()) {
      std::cerr << "rrlab: " << (options.verify ? "verify: " : "") << "nothing compared: run " << run->id
                << " stored no frames and completed no steps\n";
      return options.verify ? kExitNothingCompared : 0;
    }
    if (options.verify && !result.identical()) {
      if (result.first_mismatch)
        std::cerr << "rrlab: verify failed: frame " << *result.first_mismatch << " differs (" << result.mismatch << ")\n";
      else
        std::cerr << "rrlab: verify failed: the summary differs (" << result.summary_mismatch << ")\n";
      return 1;
    }
    return 0;
  } catch (const std::exception& e) {
    std::cerr << "rrlab: error: " << e.what() << '\n';
    return 2;
  }
}

}  // namespace rrlab::cli

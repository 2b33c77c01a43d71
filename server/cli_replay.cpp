#include <filesystem>
#include <iostream>

#include "app/resimulation.hpp"
#include "cli.hpp"
#include "storage/run_store.hpp"

namespace rrlab::cli {

// Re-simulates a stored run and prints {run, frames_compared, identical, ...}.
int replay(const ReplayOptions& options) {
  try {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(options.db, ec)) {
      std::cerr << "rrlab: error: no database file '" << options.db << "'\n";  // never create one here
      return 2;
    }
    storage::RunStore store(options.db);
    const auto run = store.run(options.run_id);
    if (!run) {
      std::cerr << "rrlab: error: no run " << options.run_id << " in " << options.db << '\n';
      return 2;
    }
    const server::ResimulationResult result = server::resimulate(store, *run, {});
    nlohmann::json out = {{"run", run->id},
                          {"frames_stored", run->frames},
                          {"frames_compared", result.frames_compared},
                          {"identical", result.identical()},
                          {"summary", summary_to_json(result.summary)}};
    if (result.first_mismatch) {
      out["first_mismatch"] = *result.first_mismatch;
      out["mismatch"] = result.mismatch;
    }
    std::cout << out.dump() << '\n';
    if (options.verify && !result.identical()) {
      std::cerr << "rrlab: verify failed: frame " << *result.first_mismatch << " differs (" << result.mismatch << ")\n";
      return 1;
    }
    return 0;
  } catch (const std::exception& e) {
    std::cerr << "rrlab: error: " << e.what() << '\n';
    return 2;
  }
}

}  // namespace rrlab::cli

// rrlab merge OUT.db IN.db...: shard databases into one, without duplicates.
#include <filesystem>
#include <iostream>
#include <nlohmann/json.hpp>

#include <rrlab/storage/run_store.hpp>
#include <rrlab/sweep/sweep_merge.hpp>

#include "cli.hpp"

namespace rrlab::cli {

int merge(const MergeOptions& options) {
  try {
    std::error_code ec;
    for (const std::string& in : options.in_dbs) {
      if (!database_exists(in)) return 2;
      if (std::filesystem::exists(options.out_db, ec) && std::filesystem::equivalent(in, options.out_db, ec)) {
        std::cerr << "rrlab: error: '" << in << "' is the output database itself\n";
        return 2;
      }
    }
    const std::filesystem::path out_path(options.out_db);
    if (out_path.has_parent_path()) std::filesystem::create_directories(out_path.parent_path());
    storage::RunStore out(options.out_db);
    nlohmann::json merged = nlohmann::json::array();
    for (const std::string& in : options.in_dbs) {
      storage::RunStore from(in);
      const sweep::MergeOutcome outcome = sweep::merge_sweep_runs(out, from);
      merged.push_back({{"from", in}, {"copied", outcome.copied}, {"already_present", outcome.already_present}});
    }
    std::cout << nlohmann::json{{"into", options.out_db}, {"merged", merged}}.dump() << '\n';
    return 0;
  } catch (const std::exception& e) {
    std::cerr << "rrlab: error: " << e.what() << '\n';
    return 2;
  }
}

}  // namespace rrlab::cli

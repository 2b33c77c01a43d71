#include <rrlab/sweep/sweep_merge.hpp>

#include <limits>
#include <map>
#include <set>
#include <stdexcept>

namespace rrlab::sweep {

MergeOutcome merge_sweep_runs(storage::RunStore& into, storage::RunStore& from) {
  MergeOutcome outcome;
  std::map<std::string, std::set<std::string>> present;  // sweep -> keys in `into`
  for (const storage::SweepRunEntry& entry : from.sweep_runs(std::nullopt)) {
    auto it = present.find(entry.row.sweep);
    if (it == present.end()) {
      const std::vector<std::string> keys = into.sweep_keys(entry.row.sweep);
      it = present.emplace(entry.row.sweep, std::set<std::string>(keys.begin(), keys.end())).first;
    }
    if (it->second.count(entry.row.key)) {
      ++outcome.already_present;
      continue;
    }
    const std::optional<storage::RunRecord> run = from.run(entry.run_id);
    if (!run) throw std::runtime_error("run " + std::to_string(entry.run_id) + " vanished while merging");
    storage::FinishedRun copy;
    copy.run = {run->scenario_name, run->scenario_json, run->method, run->params_json, run->mode,
                run->seed, run->dof, run->diagnostic_names_json, std::nullopt, std::nullopt};
    copy.summary_json = run->summary_json.value_or("null");
    copy.created = run->created;
    copy.events = from.events(run->id);
    from.frames(run->id, 0, std::numeric_limits<std::int64_t>::max(), 1, [&](const storage::StoredFrame& f) {
      copy.frames.push_back(f);
      return true;
    });
    if (into.add_sweep_run(copy, entry.row)) ++outcome.copied;
    else ++outcome.already_present;
    it->second.insert(entry.row.key);
  }
  return outcome;
}

}  // namespace rrlab::sweep

#include <rrlab/storage/resimulation.hpp>

#include <algorithm>
#include <chrono>

#include <rrlab/methods/registry_json.hpp>
#include <rrlab/sim/run_record.hpp>
#include <rrlab/sim/simulator.hpp>
#include <rrlab/storage/frame_codec.hpp>
#include <rrlab/util/nesting_depth.hpp>

namespace rrlab::storage {

using nlohmann::json;

Scenario scenario_of_run(const RunRecord& run) {
  Scenario scenario = parse_scenario_text(run.scenario_json);
  scenario.method.name = run.method;
  scenario.method.params.clear();
  const json params = parse_json(run.params_json);
  for (auto it = params.begin(); it != params.end(); ++it)
    scenario.method.params.emplace_back(it.key(), it.value().get<double>());
  return scenario;
}

NewRun new_run_of(const Scenario& scenario, const Simulator& sim, const std::string& mode) {
  NewRun run;
  run.scenario_name = scenario.name;
  run.scenario_json = scenario.json.dump();
  run.method = sim.method_name();
  run.params_json = param_values_json(sim.method()).dump();
  run.mode = mode;
  run.seed = scenario.seed;
  run.dof = sim.model().dof();
  run.diagnostic_names_json = json(sim.diagnostic_names()).dump();
  return run;
}

namespace {

// Names the first field where two packed frames differ.
std::string describe_difference(const std::string& stored, const std::string& fresh) {
  try {
    const Frame a = unpack_frame(stored), b = unpack_frame(fresh);
    if (a.step != b.step) return "step " + std::to_string(a.step) + " vs " + std::to_string(b.step);
    if (a.q.size() != b.q.size()) return "dof";
    for (Eigen::Index i = 0; i < a.q.size(); ++i)
      if (a.q[i] != b.q[i]) return "q" + std::to_string(i + 1) + " " + json(a.q[i]).dump() + " vs " + json(b.q[i]).dump();
    for (Eigen::Index i = 0; i < a.qdot.size(); ++i)
      if (a.qdot[i] != b.qdot[i]) return "qdot" + std::to_string(i + 1);
    return "metrics or diagnostics";
  } catch (const std::exception& e) {
    return e.what();
  }
}

// A stored blob's format version; an unreadable blob is compared as the
// current format (and then differs).
int stored_version(const std::string& blob) {
  try {
    return frame_blob_version(blob);
  } catch (const std::exception&) {
    return kFrameBlobVersion;
  }
}

// The result fields of a summary: what a re-simulation must reproduce (step
// times differ run to run), by the summary's format (frame.hpp, kSummaryFormat).
constexpr const char* kSummaryResultFields[] = {"steps", "collided", "min_distance", "max_tracking_error",
                                                "final_tracking_error", "joint_limit_violated", "min_joint_limit_margin",
                                                "max_condition_number", "nonfinite_steps", "max_qdot_ratio",
                                                "max_qddot_ratio", "final_q"};
constexpr const char* kSummaryFormat2Fields[] = {"obstacle_collided", "self_collided", "min_self_distance",
                                                 "rms_qddot",         "max_qddot",     "rms_jerk",
                                                 "max_jerk"};
constexpr const char* kSummaryFormat3Fields[] = {"position_limit_steps", "velocity_limit_steps"};

// A run without frames whose summary says it completed steps: as many steps, the summary compared after.
void resimulate_from_summary(Simulator& sim, const RunRecord& run, EventReplayer& replayer,
                             const std::function<void(std::int64_t, const Frame&, const std::string&)>& on_frame,
                             ResimulationResult& result) {
  const std::int64_t steps = summary_steps(run);
  if (steps == 0) return;
  std::string packed;
  for (std::int64_t seq = 0; seq < steps; ++seq) {
    replayer.apply_due(sim, long(seq));
    timed_step(sim);
    if (on_frame) {
      storage::pack_frame(sim.frame(), packed);
      on_frame(seq, sim.frame(), packed);
    }
  }
  result.summary_compared = true;
}

std::string summary_difference(const RunRecord& run, const Summary& fresh_summary) {
  const json stored = json::parse(*run.summary_json, nullptr, false);
  json fresh = summary_to_json(fresh_summary);
  const int format = stored.is_object() && stored.contains("format") && stored["format"].is_number_integer()
                         ? stored["format"].get<int>()
                         : 1;
  // format 1: `collided` meant an obstacle contact, and no link pair was checked
  if (format < 2) fresh["collided"] = fresh["obstacle_collided"];
  auto differs = [&](const char* field) {
    const json a = stored.contains(field) ? stored[field] : json(), b = fresh.contains(field) ? fresh[field] : json();
    return a != b ? std::string(field) + " " + a.dump() + " vs " + b.dump() : std::string();
  };
  for (const char* field : kSummaryResultFields)
    if (std::string d = differs(field); !d.empty()) return d;
  if (format >= 2)
    for (const char* field : kSummaryFormat2Fields)
      if (std::string d = differs(field); !d.empty()) return d;
  if (format >= 3)
    for (const char* field : kSummaryFormat3Fields)
      if (std::string d = differs(field); !d.empty()) return d;
  return "";
}

}  // namespace

std::int64_t summary_steps(const RunRecord& run) {
  if (!run.summary_json) return 0;
  const json stored = json::parse(*run.summary_json, nullptr, false);
  if (!stored.is_object() || !stored.contains("steps") || !stored["steps"].is_number_integer()) return 0;
  const std::int64_t steps = stored["steps"].get<std::int64_t>();
  return steps > 0 && steps <= std::int64_t(ScenarioLimits::max_steps) * 16 ? steps : 0;
}

json verification_json(const ResimulationResult& result) {
  json out = {{"identical", result.compared() ? json(result.identical()) : json()},
              {"compared", result.compared()},
              {"frames_compared", result.frames_compared},
              {"first_mismatch", result.first_mismatch ? json(*result.first_mismatch) : json()},
              {"mismatch", result.summary_mismatch.empty() ? result.mismatch : "summary: " + result.summary_mismatch}};
  if (result.summary_compared) out["summary_compared"] = true;
  if (!result.compared()) out["reason"] = kNothingCompared;
  return out;
}

ResimulationResult resimulate(RunStore& store, const RunRecord& run,
                              const std::function<void(std::int64_t, const Frame&, const std::string&)>& on_frame) {
  Simulator sim(scenario_of_run(run));
  sim.set_total_steps(ScenarioLimits::max_steps * 16);  // resets restart the step count; seq bounds the loop
  std::vector<RecordedEvent> events;
  for (const StoredEvent& e : store.events(run.id))
    events.push_back({long(e.seq), e.kind, parse_json(e.payload_json)});
  EventReplayer replayer(events);
  ResimulationResult result;
  std::string packed, packed_as_stored;
  constexpr std::int64_t chunk = 4096;
  std::vector<std::string> stored;
  for (std::int64_t from = 0; from < run.frames; from += chunk) {
    stored.clear();
    store.frames(run.id, from, std::min(run.frames, from + chunk) - 1, 1, [&](const storage::StoredFrame& f) {
      stored.push_back(f.data);
      return true;
    });
    for (size_t i = 0; i < stored.size(); ++i) {
      const std::int64_t seq = from + std::int64_t(i);
      replayer.apply_due(sim, long(seq));
      timed_step(sim);
      storage::pack_frame(sim.frame(), packed);
      if (on_frame) on_frame(seq, sim.frame(), packed);
      ++result.frames_compared;
      if (result.first_mismatch) continue;
      // a run stored in an older blob format is compared in its own format
      const std::string* fresh = &packed;
      const int version = stored_version(stored[i]);
      if (version != kFrameBlobVersion) {
        storage::pack_frame(sim.frame(), packed_as_stored, version);
        fresh = &packed_as_stored;
      }
      if (*fresh != stored[i]) {
        result.first_mismatch = seq;
        result.mismatch = describe_difference(stored[i], *fresh);
      }
    }
  }
  if (run.frames == 0) resimulate_from_summary(sim, run, replayer, on_frame, result);
  result.summary = sim.summary();
  if (result.summary_compared) result.summary_mismatch = summary_difference(run, result.summary);
  return result;
}

}  // namespace rrlab::storage

#include <rrlab/sweep/summaries_csv.hpp>

#include <cstdio>
#include <nlohmann/json.hpp>
#include <unordered_map>

#include <rrlab/util/nesting_depth.hpp>

namespace rrlab::sweep {

namespace {

std::string field(const nlohmann::json& value) {
  if (value.is_null()) return "";
  if (value.is_boolean()) return value.get<bool>() ? "1" : "0";
  if (value.is_number_float()) {
    char buf[40];
    std::snprintf(buf, sizeof buf, "%.17g", value.get<double>());
    return buf;
  }
  if (value.is_number()) return value.dump();
  return "";
}

std::string quoted(const std::string& text) {
  if (text.find_first_of(",\"\n") == std::string::npos) return text;
  std::string out = "\"";
  for (char c : text) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

constexpr const char* kSummaryColumns[] = {"steps", "collided", "min_distance", "self_collided", "min_self_distance",
                                           "max_tracking_error",
                                           "final_tracking_error", "joint_limit_violated", "min_joint_limit_margin",
                                           "max_qdot_ratio", "max_qddot_ratio", "max_condition_number",
                                           "nonfinite_steps", "rms_qddot", "max_qddot", "rms_jerk", "max_jerk",
                                           "position_limit_steps", "velocity_limit_steps"};

// The generated cases' difficulty (witness.difficulty), empty for other runs.
constexpr const char* kDifficultyColumns[] = {"clearance",  "limit_margin",       "gap_width",
                                              "path_length", "duration",          "min_manipulability",
                                              "interpolation_error", "peak_joint_speed", "blocking_obstacles",
                                              "tight_obstacles"};

}  // namespace

void write_summaries_csv(std::ostream& out, const std::vector<SweepCase>& cases,
                         const std::vector<storage::SweepRunEntry>& stored) {
  std::unordered_map<std::string, const storage::SweepRunEntry*> by_key;
  for (const storage::SweepRunEntry& e : stored) by_key[e.row.key] = &e;
  out << "key,scenario_key,config,family,seed,success,failure_mode,failure_t,run";
  for (const char* column : kSummaryColumns) out << ',' << column;
  for (const char* column : kDifficultyColumns) out << ",difficulty_" << column;
  out << ",step_us_mean,step_us_p50,step_us_p99\n";
  for (const SweepCase& c : cases) {
    const auto it = by_key.find(c.key);
    if (it == by_key.end()) continue;
    const storage::SweepRunEntry& e = *it->second;
    const nlohmann::json summary = e.summary_json ? parse_json(*e.summary_json) : nlohmann::json::object();
    out << quoted(c.key) << ',' << quoted(c.scenario_key) << ',' << quoted(c.config_key) << ',' << quoted(c.family)
        << ',' << e.seed << ',' << (e.row.success ? 1 : 0) << ',' << quoted(e.row.failure_mode.value_or(""))
        << ',' << (e.row.failure_t ? field(*e.row.failure_t) : "") << ',' << e.run_id;
    for (const char* column : kSummaryColumns) out << ',' << field(summary.value(column, nlohmann::json()));
    const nlohmann::json difficulty = e.difficulty_json ? parse_json(*e.difficulty_json) : nlohmann::json::object();
    for (const char* column : kDifficultyColumns)
      out << ',' << field(difficulty.is_object() ? difficulty.value(column, nlohmann::json()) : nlohmann::json());
    const nlohmann::json step = summary.value("step_us", nlohmann::json::object());
    out << ',' << field(step.value("mean", nlohmann::json())) << ',' << field(step.value("p50", nlohmann::json()))
        << ',' << field(step.value("p99", nlohmann::json())) << '\n';
  }
}

}  // namespace rrlab::sweep

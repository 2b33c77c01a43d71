// A sweep's success criteria ("success" in the spec) and the verdict on one
// run's summary. The verdict is stored with the run (sweep_runs.success).
#pragma once

#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "sim/frame.hpp"

namespace rrlab::sweep {

struct SuccessCriteria {
  std::optional<double> max_tracking_error;        // m: summary.max_tracking_error must not exceed it
  std::optional<double> max_final_tracking_error;  // m
  std::optional<double> min_distance;              // m: the run's minimum clearance must reach it
  bool collision = false;                          // false: a collision fails the run
  bool joint_limits = true;                        // true: a joint-limit violation fails the run
  bool nonfinite = false;                          // false: a non-finite method output fails the run
};

// Throws ScenarioError naming `path.KEY`.
SuccessCriteria parse_success_criteria(const nlohmann::json& value, const std::string& path);
bool judge_success(const SuccessCriteria& criteria, const Summary& summary);

}  // namespace rrlab::sweep

// A sweep's success criteria ("success" in the spec) and the verdict on one
// run's summary. The verdict is stored with the run (sweep_runs.success).
#pragma once

#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include <rrlab/sim/frame.hpp>

namespace rrlab::sweep {

struct SuccessCriteria {
  std::optional<double> max_tracking_error;        // m: the tracking error must not exceed it ...
  double settle_time = 0;                          // s: ... from this time on (a start off the path gets
                                                   // this long to reach it; the watch judges that part)
  std::optional<double> max_final_tracking_error;  // m
  std::optional<double> min_distance;              // m: the run's minimum clearance must reach it
  bool collision = false;                          // false: a collision fails the run
  bool joint_limits = true;                        // true: a joint-limit violation fails the run
  bool nonfinite = false;                          // false: a non-finite method output fails the run
  bool joint_speeds = false;                       // true: a joint faster than its velocity limit fails it
};

// A joint speed counts as past its limit beyond this fraction (a method that
// rides the bound lands on it up to rounding).
inline constexpr double kJointSpeedTolerance = 1e-6;

// Throws ScenarioError naming `path.KEY`.
SuccessCriteria parse_success_criteria(const nlohmann::json& value, const std::string& path);
// The verdict from the summary. With a settle time the tracking bound is not
// in the summary: the FailureWatch of the run judges it (tracking_held()).
bool judge_success(const SuccessCriteria& criteria, const Summary& summary);

}  // namespace rrlab::sweep

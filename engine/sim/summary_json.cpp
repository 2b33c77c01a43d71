#include <cmath>

#include <rrlab/sim/frame.hpp>

namespace rrlab {

nlohmann::json finite_or_null(double value) {
  return std::isfinite(value) ? nlohmann::json(value) : nlohmann::json(nullptr);
}

nlohmann::json finite_or_null(const std::optional<double>& value) {
  return value ? finite_or_null(*value) : nlohmann::json(nullptr);
}

nlohmann::json finite_or_null(const Eigen::VectorXd& values) {
  nlohmann::json array = nlohmann::json::array();
  for (Eigen::Index i = 0; i < values.size(); ++i) array.push_back(finite_or_null(values[i]));
  return array;
}

nlohmann::json summary_to_json(const Summary& s) {
  nlohmann::json j;
  j["scenario"] = s.scenario;
  j["method"] = s.method;
  j["steps"] = s.steps;
  j["format"] = kSummaryFormat;
  j["collided"] = s.collided;
  j["obstacle_collided"] = s.obstacle_collided;
  j["self_collided"] = s.self_collided;
  j["min_distance"] = finite_or_null(s.min_distance);
  j["min_self_distance"] = finite_or_null(s.min_self_distance);
  j["max_tracking_error"] = finite_or_null(s.max_tracking_error);
  j["final_tracking_error"] = finite_or_null(s.final_tracking_error);
  j["joint_limit_violated"] = s.joint_limit_violated;
  j["min_joint_limit_margin"] = finite_or_null(s.min_joint_limit_margin);
  j["max_qdot_ratio"] = finite_or_null(s.max_qdot_ratio);
  j["max_qddot_ratio"] = finite_or_null(s.max_qddot_ratio);
  j["position_limit_steps"] = s.position_limit_steps;
  j["velocity_limit_steps"] = s.velocity_limit_steps ? nlohmann::json(*s.velocity_limit_steps) : nlohmann::json(nullptr);
  j["max_condition_number"] = finite_or_null(s.max_condition_number);
  j["nonfinite_steps"] = s.nonfinite_steps;
  j["rms_qddot"] = finite_or_null(s.smoothness.rms_qddot);
  j["max_qddot"] = finite_or_null(s.smoothness.max_qddot);
  j["rms_jerk"] = finite_or_null(s.smoothness.rms_jerk);
  j["max_jerk"] = finite_or_null(s.smoothness.max_jerk);
  j["final_q"] = finite_or_null(s.final_q);
  j["step_us"] = {{"mean", s.step_us.mean}, {"p50", s.step_us.p50}, {"p99", s.step_us.p99}};
  return j;
}

}  // namespace rrlab

#include <rrlab/sweep/success_criteria.hpp>

#include <cmath>

#include <rrlab/scenario/json_reader.hpp>

namespace rrlab::sweep {

namespace {
bool boolean(JsonObject& object, const std::string& key, bool def) {
  if (!object.has(key)) return def;
  const nlohmann::json& v = object.raw(key);
  if (!v.is_boolean()) throw ScenarioError(object.child(key), "must be true or false, got " + json_type_name(v));
  return v.get<bool>();
}

std::optional<double> non_negative(JsonObject& object, const std::string& key) {
  const std::optional<double> v = object.optional_number(key);
  if (v && *v < 0) throw ScenarioError(object.child(key), "must be >= 0 m");
  return v;
}
}  // namespace

SuccessCriteria parse_success_criteria(const nlohmann::json& value, const std::string& path) {
  JsonObject object(value, path);
  object.check_keys(
      {"max_tracking_error", "settle_time", "max_final_tracking_error", "min_distance", "collision", "joint_limits",
       "joint_speeds", "nonfinite"});
  SuccessCriteria c;
  c.max_tracking_error = non_negative(object, "max_tracking_error");
  if (const std::optional<double> settle = object.optional_number("settle_time")) {
    if (!(*settle >= 0)) throw ScenarioError(object.child("settle_time"), "must be >= 0 s");
    if (!c.max_tracking_error)
      throw ScenarioError(object.child("settle_time"), "needs max_tracking_error: it says when that bound starts");
    c.settle_time = *settle;
  }
  c.max_final_tracking_error = non_negative(object, "max_final_tracking_error");
  c.min_distance = object.optional_number("min_distance");
  c.collision = boolean(object, "collision", false);
  c.joint_limits = boolean(object, "joint_limits", true);
  c.nonfinite = boolean(object, "nonfinite", false);
  c.joint_speeds = boolean(object, "joint_speeds", false);
  return c;
}

bool judge_success(const SuccessCriteria& c, const Summary& s) {
  // a NaN error or distance never passes a bound
  if (c.max_tracking_error && c.settle_time == 0 && !(s.max_tracking_error <= *c.max_tracking_error)) return false;
  if (c.max_final_tracking_error && !(s.final_tracking_error <= *c.max_final_tracking_error)) return false;
  if (c.min_distance && !(s.min_distance >= *c.min_distance)) return false;
  if (!c.collision && s.collided) return false;
  if (c.joint_limits && s.joint_limit_violated) return false;
  if (!c.nonfinite && s.nonfinite_steps > 0) return false;
  // without velocity limits there is nothing to exceed
  if (c.joint_speeds && s.max_qdot_ratio && !(*s.max_qdot_ratio <= 1 + kJointSpeedTolerance)) return false;
  return true;
}

}  // namespace rrlab::sweep

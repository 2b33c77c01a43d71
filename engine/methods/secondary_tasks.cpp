#include <rrlab/methods/secondary_tasks.hpp>

#include <cmath>

namespace rrlab {

ClosestObstaclePoint closest_obstacle_point(const DistanceTable& distances) {
  ClosestObstaclePoint cp;
  if (distances.min_link < 0) return cp;
  const LinkObstacleDistance& pair = distances.at(distances.min_link, distances.min_obstacle);
  cp.found = true;
  cp.link = distances.min_link;
  cp.distance = pair.distance;
  cp.point = pair.on_link;
  cp.normal = pair.normal;
  return cp;
}

int point_rows(const Model& model) { return model.kind == ModelKind::planar ? 2 : 3; }

void closest_point_jacobian(const Model& model, const KinematicsData& kin,
                            const ClosestObstaclePoint& cp, Eigen::MatrixXd& scratch,
                            Eigen::MatrixXd& jac) {
  point_jacobian_linear(model, kin, cp.link, cp.point, scratch);
  jac = scratch.topRows(jac.rows());
}

void joint_range_centres(const JointLimits& limits, Eigen::VectorXd& centre,
                         Eigen::VectorXd& inv_range_sq) {
  const Eigen::Index n = limits.lower.size();
  centre.setZero(n);
  inv_range_sq.setZero(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    if (!std::isfinite(limits.lower[i]) || !std::isfinite(limits.upper[i])) continue;
    const double range = limits.upper[i] - limits.lower[i];
    centre[i] = 0.5 * (limits.lower[i] + limits.upper[i]);
    if (range > 0) inv_range_sq[i] = 1.0 / (range * range);
  }
}

ParamSpec secondary_task_spec() {
  return {"secondary", "Secondary task", "",
          "obstacle: keep the closest link point at the influence distance; "
          "joint_centring: drive joints to mid-range",
          0, 0, 1, 1, {"obstacle", "joint_centring"}};
}

ParamSpec influence_distance_spec(double def) {
  return {"influence", "Influence distance", "m",
          "distance below which obstacle avoidance acts", def, 0.001, 10.0, 0.01, {}};
}

ParamSpec secondary_gain_spec(double def) {
  return {"gain", "Secondary gain", "1/s", "gain of the secondary task", def, 0.0, 1000.0, 0.1, {}};
}

ParamSpec damping_spec(double def) {
  return {"lambda", "Damping λ", "", "damping factor of the damped least-squares inverse", def,
          0.0, 10.0, 0.001, {}};
}

ParamSpec secondary_damping_spec(double def) {
  return {"secondary_lambda", "Secondary damping λ₂", "m",
          "damping of the secondary task's inverse; 0: the exact pseudoinverse", def, 0.0, 10.0, 0.01, {}};
}

}  // namespace rrlab

namespace rrlab {

DistanceTask distance_task(const StepInput& in, double influence, double gain,
                           Eigen::MatrixXd& scratch3n, Eigen::MatrixXd& j2) {
  DistanceTask task;
  const ClosestObstaclePoint cp = closest_obstacle_point(in.distances);
  if (!cp.found) return task;
  task.distance = cp.distance;
  if (cp.distance >= influence) return task;
  point_jacobian_linear(in.model, in.kin, cp.link, cp.point, scratch3n);
  j2.noalias() = cp.normal.transpose() * scratch3n;  // ∂d/∂q = nᵀ J_p
  task.active = true;
  task.rate = gain * (influence - cp.distance);
  return task;
}

}  // namespace rrlab

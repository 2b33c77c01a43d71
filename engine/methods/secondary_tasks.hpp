// Pieces shared by the baselines' secondary tasks: the closest link point to
// any obstacle, its Jacobian, and joint-range helpers.
#pragma once

#include <Eigen/Core>

#include <rrlab/collision/collision_world.hpp>
#include <rrlab/kinematics/kinematics.hpp>
#include <rrlab/methods/method.hpp>
#include <rrlab/model/model.hpp>

namespace rrlab {

struct ClosestObstaclePoint {
  bool found = false;
  int link = -1;
  double distance = 0;
  Eigen::Vector3d point = Eigen::Vector3d::Zero();   // on the link axis
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();  // obstacle -> link
};

// The globally closest link–obstacle pair of the table.
ClosestObstaclePoint closest_obstacle_point(const DistanceTable& distances);

// Workspace rows of a point velocity: 2 (x, y) for planar models, else 3.
int point_rows(const Model& model);

// Linear Jacobian rows (point_rows x n) of the closest point; `scratch` is 3 x n.
void closest_point_jacobian(const Model& model, const KinematicsData& kin,
                            const ClosestObstaclePoint& cp, Eigen::MatrixXd& scratch,
                            Eigen::MatrixXd& jac);

// Mid-range of each joint (0 where a bound is missing) and 1/range² weights
// (0 where unbounded: such joints are free of the joint-range criterion).
void joint_range_centres(const JointLimits& limits, Eigen::VectorXd& centre,
                         Eigen::VectorXd& inv_range_sq);

// Shared specs of the obstacle / joint-centring secondary task.
ParamSpec secondary_task_spec();
ParamSpec influence_distance_spec(double def);
ParamSpec secondary_gain_spec(double def);
ParamSpec damping_spec(double def);
// Damping of the secondary task's inverse (0: the exact pseudoinverse).
ParamSpec secondary_damping_spec(double def);

}  // namespace rrlab

namespace rrlab {

// Nakamura's distance task for the closest pair: x₂ = d, J₂ = nᵀJ_p (1 x n),
// ẋ₂ = gain·(d0 − d). False (and nothing written) when no obstacle is nearer than d0.
struct DistanceTask {
  bool active = false;
  double distance = 0;
  double rate = 0;  // ẋ₂
};
DistanceTask distance_task(const StepInput& in, double influence, double gain,
                           Eigen::MatrixXd& scratch3n, Eigen::MatrixXd& j2);

}  // namespace rrlab

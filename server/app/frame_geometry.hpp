// What a WebSocket frame draws beyond the simulator's own record: each link's
// nearest obstacle, the velocity manipulability ellipsoid at the end-effector
// and the links of ghost configurations. Computed when a frame is published
// (live runs and replays alike) from the frame's q, the model and the scene as
// it is then, into workspaces sized once: no allocation in steady state.
#pragma once

#include <Eigen/Core>
#include <cstdint>

#include <rrlab/collision/collision_world.hpp>
#include <rrlab/collision/scene.hpp>
#include <rrlab/kinematics/kinematics.hpp>
#include <rrlab/model/model.hpp>

namespace rrlab::server {

// Yoshikawa's velocity manipulability ellipsoid {J_pos q̇ : ‖q̇‖ ≤ 1}: semi-axes
// σ_i u_i from the SVD J_pos = U Σ Vᵀ (m/s per unit ‖q̇‖), in world coordinates.
struct ManipulabilityEllipsoid {
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();  // the end-effector position
  Eigen::Matrix3d axes = Eigen::Matrix3d::Zero();    // columns: semi-axes, longest first (zero when missing)
};

// From the position rows of a task Jacobian (xy: 2 rows, padded with z = 0;
// xyz: 3; pose: the first 3 of 6), by the eigen decomposition of the 3×3
// J_pos J_posᵀ (eigenvalues σ_i²). Allocation-free.
ManipulabilityEllipsoid velocity_ellipsoid(const Eigen::MatrixXd& task_jacobian, const Eigen::Vector3d& centre);

class FrameGeometry {
 public:
  FrameGeometry(const Model& model, const Scene& scene, TaskSpace space);

  // Kinematics, task Jacobian, link–obstacle distances and the ellipsoid at q.
  // A scene_version other than the last one re-reads the obstacles' shapes
  // (added, removed or resized); otherwise only their poses are read.
  void update(const Model& model, const Scene& scene, std::uint64_t scene_version, const Eigen::VectorXd& q);

  const KinematicsData& kinematics() const { return kin_; }
  const DistanceTable& distances() const { return distances_; }
  const ManipulabilityEllipsoid& ellipsoid() const { return ellipsoid_; }

  // Forward kinematics of a ghost configuration (q of the model's dof) into a
  // reused workspace, valid until the next call.
  const KinematicsData& ghost_kinematics(const Model& model, const Eigen::VectorXd& q);

 private:
  TaskSpace space_;
  KinematicsData kin_, ghost_kin_;
  Eigen::MatrixXd task_jacobian_;
  CollisionWorld collision_;
  DistanceTable distances_;
  ManipulabilityEllipsoid ellipsoid_;
  std::uint64_t synced_scene_version_ = 0;  // 0: shapes not yet read for any version
};

}  // namespace rrlab::server

#include <rrlab/server/app/frame_geometry.hpp>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>

namespace rrlab::server {

ManipulabilityEllipsoid velocity_ellipsoid(const Eigen::MatrixXd& task_jacobian, const Eigen::Vector3d& centre) {
  ManipulabilityEllipsoid ellipsoid;
  ellipsoid.centre = centre;
  const Eigen::Index position_rows = std::min<Eigen::Index>(3, task_jacobian.rows());
  // J_pos J_posᵀ by row dot products: a fixed 3×3 whatever the dof (rows beyond J_pos stay 0)
  Eigen::Matrix3d jjt = Eigen::Matrix3d::Zero();
  for (Eigen::Index r = 0; r < position_rows; ++r)
    for (Eigen::Index c = r; c < position_rows; ++c)
      jjt(r, c) = jjt(c, r) = task_jacobian.row(r).dot(task_jacobian.row(c));
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(jjt);  // eigenvalues ascending
  if (eigen.info() != Eigen::Success) {
    ellipsoid.axes.setConstant(std::numeric_limits<double>::quiet_NaN());  // drawn as nulls
    return ellipsoid;
  }
  for (int i = 0; i < 3; ++i) {
    const int k = 2 - i;  // longest first
    const double sigma = std::sqrt(std::max(0.0, eigen.eigenvalues()[k]));
    ellipsoid.axes.col(i) = sigma * eigen.eigenvectors().col(k);
  }
  return ellipsoid;
}

FrameGeometry::FrameGeometry(const Model& model, const Scene& scene, TaskSpace space)
    : space_(space),
      kin_(model),
      ghost_kin_(model),
      task_jacobian_(task_rows(space), model.dof()),
      collision_(model, scene) {
  distances_.resize(model.link_count(), int(scene.obstacles.size()));
}

void FrameGeometry::update(const Model& model, const Scene& scene, std::uint64_t scene_version,
                           const Eigen::VectorXd& q) {
  forward_kinematics(model, q, kin_);
  task_jacobian(model, kin_, space_, task_jacobian_);
  collision_.sync(scene, scene_version != synced_scene_version_);
  synced_scene_version_ = scene_version;
  collision_.compute(kin_, distances_);
  ellipsoid_ = velocity_ellipsoid(task_jacobian_, kin_.end_effector().translation());
}

const KinematicsData& FrameGeometry::ghost_kinematics(const Model& model, const Eigen::VectorXd& q) {
  forward_kinematics(model, q, ghost_kin_);
  return ghost_kin_;
}

}  // namespace rrlab::server

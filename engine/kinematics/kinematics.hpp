// Forward kinematics and Jacobians over a Model, into a preallocated
// workspace (model = constant description, KinematicsData = per-step data).
#pragma once

#include <Eigen/Core>
#include <Eigen/Eigenvalues>
#include <vector>

#include <rrlab/model/model.hpp>

namespace rrlab {

// Task spaces select rows of the 6-row point Jacobian [linear; angular].
enum class TaskSpace { xy, xyz, pose };
int task_rows(TaskSpace space);
const char* to_string(TaskSpace space);

struct KinematicsData {
  explicit KinematicsData(const Model& model);

  Eigen::Matrix3Xd axis_points;  // a point on each joint axis (world)
  Eigen::Matrix3Xd axis_dirs;    // each joint axis (world, unit)
  std::vector<Eigen::Isometry3d> joint_frames;  // frame after each joint
  Eigen::Matrix3Xd link_start, link_end;        // each link's segment (world)

  const Eigen::Isometry3d& end_effector() const { return joint_frames.back(); }
};

// All joint frames and link segments in one pass (no allocation).
void forward_kinematics(const Model& model, const Eigen::VectorXd& q, KinematicsData& data);
// The same for a q that differs from the one `data` was last computed for
// only in joints first.. (the frames before joint `first` are kept): the
// same numbers as forward_kinematics, for the work of the changed joints.
// Without link_segments the link segments are left as they are (a caller
// that needs only frames and axes, such as an iteration on the end-effector).
void forward_kinematics_from(const Model& model, const Eigen::VectorXd& q, KinematicsData& data, int first,
                             bool link_segments = true);

// 6 x n Jacobian [v; w] of the world point p rigidly attached to `link`;
// columns of joints beyond the link are zero. `jac` must be 6 x dof.
void point_jacobian(const Model& model, const KinematicsData& data, int link,
                    const Eigen::Vector3d& p, Eigen::Ref<Eigen::MatrixXd> jac);
// 3 x n, linear rows only.
void point_jacobian_linear(const Model& model, const KinematicsData& data, int link,
                           const Eigen::Vector3d& p, Eigen::Ref<Eigen::MatrixXd> jac);
// Rows of the end-effector Jacobian for a task space (m x n, m = task_rows).
void task_jacobian(const Model& model, const KinematicsData& data, TaskSpace space,
                   Eigen::Ref<Eigen::MatrixXd> jac);
// Only the columns columns[0..count) of task_jacobian; the others are left as they are.
void task_jacobian_columns(const Model& model, const KinematicsData& data, TaskSpace space, const int* columns,
                           int count, Eigen::Ref<Eigen::MatrixXd> jac);

// Singular values of an m x n Jacobian (m <= n) from the eigenvalues of J Jᵀ;
// preallocated for one m.
class JacobianConditioning {
 public:
  JacobianConditioning(int rows, int cols);
  void compute(const Eigen::MatrixXd& jac);
  double manipulability() const { return manipulability_; }  // sqrt(det(J Jᵀ))
  double condition_number() const { return condition_; }     // σmax / σmin (inf if singular)
  double sigma_min() const { return sigma_min_; }
  double sigma_max() const { return sigma_max_; }

 private:
  Eigen::MatrixXd jjt_;
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig_;
  double manipulability_ = 0, condition_ = 0, sigma_min_ = 0, sigma_max_ = 0;
};

}  // namespace rrlab

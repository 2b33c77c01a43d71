#include <rrlab/kinematics/kinematics.hpp>

#include <cmath>
#include <limits>
#include <string>

#include <rrlab/util/check.hpp>

namespace rrlab {

int task_rows(TaskSpace space) {
  switch (space) {
    case TaskSpace::xy: return 2;
    case TaskSpace::xyz: return 3;
    case TaskSpace::pose: return 6;
  }
  return 0;
}

const char* to_string(TaskSpace space) {
  switch (space) {
    case TaskSpace::xy: return "xy";
    case TaskSpace::xyz: return "xyz";
    case TaskSpace::pose: return "pose";
  }
  return "?";
}

KinematicsData::KinematicsData(const Model& model)
    : axis_points(3, model.dof()),
      axis_dirs(3, model.dof()),
      joint_frames(model.dof(), Eigen::Isometry3d::Identity()),
      link_start(3, model.link_count()),
      link_end(3, model.link_count()) {}

namespace {
// Rodrigues: rotation by `angle` about the unit `axis`.
Eigen::Matrix3d axis_rotation(const Eigen::Vector3d& axis, double angle) {
  const double c = std::cos(angle), s = std::sin(angle), v = 1.0 - c;
  const double x = axis.x(), y = axis.y(), z = axis.z();
  Eigen::Matrix3d r;
  r << c + x * x * v, x * y * v - z * s, x * z * v + y * s,  //
      y * x * v + z * s, c + y * y * v, y * z * v - x * s,   //
      z * x * v - y * s, z * y * v + x * s, c + z * z * v;
  return r;
}

// rot ← rot · R(axis, angle); k: the plan's axis (e_k, or −1). About a
// coordinate axis e_k (planar, DH and most URDF joints) R has c on e_i,
// e_j, ±s off the diagonal, c + (1 − c) on e_k and zeros elsewhere
// (Rodrigues with two zero components): two columns mixed instead of a
// 3 x 3 product, the same numbers since the zeros add nothing. Any other
// axis takes the product.
void rotate_about(Eigen::Matrix3d& rot, const Eigen::Vector3d& axis, int k, double angle) {
  if (k < 0) {
    rot = rot * axis_rotation(axis, angle);
    return;
  }
  double s, c;
  ::sincos(angle, &s, &c);  // one call, as the compiler makes of axis_rotation's cos and sin
  const double v = 1.0 - c;
  const int i = (k + 1) % 3, j = (k + 2) % 3;
  const Eigen::Vector3d ri = rot.col(i), rj = rot.col(j);
  rot.col(i) = ri * c + rj * s;   // R e_i = c e_i + s e_j
  rot.col(j) = rj * c - ri * s;   // R e_j = −s e_i + c e_j
  rot.col(k) *= c + v;            // R e_k = (c + z²v) e_k
}

// rot ← rot · m for a fixed joint rotation m (a URDF origin's rpy, a DH
// twist) of the plan's kind: the identity changes nothing; about a
// coordinate axis e_k (m e_k = e_k, e_kᵀ m = e_kᵀ) it mixes two columns;
// the zeros a full product would add change nothing.
void multiply_fixed(Eigen::Matrix3d& rot, const Eigen::Matrix3d& m, int kind) {
  if (kind == JointPlan::kIdentity) return;
  if (kind == JointPlan::kAnyRotation) {
    rot = rot * m;
    return;
  }
  const int k = kind, i = (k + 1) % 3, j = (k + 2) % 3;
  const Eigen::Vector3d ri = rot.col(i), rj = rot.col(j);
  rot.col(i) = ri * m(i, i) + rj * m(j, i);
  rot.col(j) = ri * m(i, j) + rj * m(j, j);
}

// The public entry points' checks of their caller's input (util/check.hpp):
// sizes and indices a caller chooses, never assert (Release drops it).
bool kinematics_data_fits(const Model& model, const KinematicsData& data) {
  return int(data.joint_frames.size()) == model.dof() && data.axis_dirs.cols() == model.dof() &&
         data.link_start.cols() == model.link_count();
}
const char* const kKinematicsDataMisfit = "the KinematicsData was made for a model of another size";
std::string jacobian_size_text(Eigen::Index rows, Eigen::Index cols, int want_rows, int want_cols) {
  return "jac is " + std::to_string(rows) + " x " + std::to_string(cols) + ", not " + std::to_string(want_rows) +
         " x " + std::to_string(want_cols);
}
std::string index_range_text(const char* what, int index, int count) {
  return std::string(what) + " " + std::to_string(index) + " outside 0.." + std::to_string(count - 1);
}
}  // namespace

void forward_kinematics(const Model& model, const Eigen::VectorXd& q, KinematicsData& data) {
  forward_kinematics_from(model, q, data, 0);
}

void forward_kinematics_from(const Model& model, const Eigen::VectorXd& q, KinematicsData& data, int first,
                             bool link_segments) {
  RRLAB_CHECK(q.size() == model.dof(), "q has " + std::to_string(q.size()) + " entries for a model of " +
                                           std::to_string(model.dof()) + " joints");
  RRLAB_CHECK(first >= 0 && first <= model.dof(),
              "first joint " + std::to_string(first) + " outside 0.." + std::to_string(model.dof()));
  RRLAB_CHECK(kinematics_data_fits(model, data), kKinematicsDataMisfit);
  // the frame before joint `first`: the base, or the one data holds after joint first − 1
  const Eigen::Isometry3d& before = first == 0 ? model.base : data.joint_frames[first - 1];
  Eigen::Matrix3d rot = before.linear();
  Eigen::Vector3d pos = before.translation();
  const bool planned = model.joint_plans.size() == model.joints.size();
  for (int j = first; j < model.dof(); ++j) {
    const Joint& joint = model.joints[j];
    const JointPlan plan = planned ? model.joint_plans[j] : JointPlan::of(joint);
    // frame before the motion: T * pre
    if (plan.pre_translation) pos += rot * joint.pre.translation();
    multiply_fixed(rot, joint.pre.linear(), plan.pre_rotation);
    data.axis_points.col(j) = pos;
    data.axis_dirs.col(j) = rot * joint.axis;
    if (joint.type == JointType::revolute) {
      rotate_about(rot, joint.axis, plan.axis, q[j]);
    } else {
      pos += data.axis_dirs.col(j) * q[j];
    }
    pos += rot * joint.post.translation();
    multiply_fixed(rot, joint.post.linear(), plan.post_rotation);
    data.joint_frames[j].linear() = rot;
    data.joint_frames[j].translation() = pos;
  }
  if (!link_segments) return;
  Eigen::Vector3d start = model.base.translation();
  for (int i = 0; i < model.link_count(); ++i) {
    data.link_start.col(i) = start;
    start = data.joint_frames[model.links[i].last_joint].translation();
    data.link_end.col(i) = start;
  }
}

void point_jacobian(const Model& model, const KinematicsData& data, int link,
                    const Eigen::Vector3d& p, Eigen::Ref<Eigen::MatrixXd> jac) {
  RRLAB_CHECK(link >= 0 && link < model.link_count(), index_range_text("link", link, model.link_count()));
  RRLAB_CHECK(jac.rows() == 6 && jac.cols() == model.dof(), jacobian_size_text(jac.rows(), jac.cols(), 6, model.dof()));
  RRLAB_CHECK(kinematics_data_fits(model, data), kKinematicsDataMisfit);
  const int last = model.links[link].last_joint;
  for (int j = 0; j <= last; ++j) {
    const Eigen::Vector3d axis = data.axis_dirs.col(j);
    if (model.joints[j].type == JointType::revolute) {
      jac.col(j).head<3>() = axis.cross(p - data.axis_points.col(j));
      jac.col(j).tail<3>() = axis;
    } else {
      jac.col(j).head<3>() = axis;
      jac.col(j).tail<3>().setZero();
    }
  }
  jac.rightCols(model.dof() - last - 1).setZero();
}

void point_jacobian_linear(const Model& model, const KinematicsData& data, int link,
                           const Eigen::Vector3d& p, Eigen::Ref<Eigen::MatrixXd> jac) {
  RRLAB_CHECK(link >= 0 && link < model.link_count(), index_range_text("link", link, model.link_count()));
  RRLAB_CHECK(jac.rows() == 3 && jac.cols() == model.dof(), jacobian_size_text(jac.rows(), jac.cols(), 3, model.dof()));
  RRLAB_CHECK(kinematics_data_fits(model, data), kKinematicsDataMisfit);
  const int last = model.links[link].last_joint;
  for (int j = 0; j <= last; ++j) {
    const Eigen::Vector3d axis = data.axis_dirs.col(j);
    if (model.joints[j].type == JointType::revolute)
      jac.col(j) = axis.cross(p - data.axis_points.col(j));
    else
      jac.col(j) = axis;
  }
  jac.rightCols(model.dof() - last - 1).setZero();
}

namespace {
// Column j of the end-effector Jacobian in the rows of `space`.
void task_jacobian_column(const Model& model, const KinematicsData& data, const Eigen::Vector3d& p, int rows, int j,
                          Eigen::Ref<Eigen::MatrixXd> jac) {
  const Eigen::Vector3d axis = data.axis_dirs.col(j);
  const bool revolute = model.joints[j].type == JointType::revolute;
  const Eigen::Vector3d lin = revolute ? Eigen::Vector3d(axis.cross(p - data.axis_points.col(j))) : axis;
  if (rows == 2) {
    jac.col(j) = lin.head<2>();
  } else {
    jac.col(j).head<3>() = lin;
    if (rows == 6) jac.col(j).tail<3>() = revolute ? axis : Eigen::Vector3d::Zero();
  }
}
}  // namespace

void task_jacobian(const Model& model, const KinematicsData& data, TaskSpace space,
                   Eigen::Ref<Eigen::MatrixXd> jac) {
  RRLAB_CHECK(jac.rows() == task_rows(space) && jac.cols() == model.dof(),
              jacobian_size_text(jac.rows(), jac.cols(), task_rows(space), model.dof()));
  RRLAB_CHECK(kinematics_data_fits(model, data), kKinematicsDataMisfit);
  const Eigen::Vector3d p = data.end_effector().translation();
  for (int j = 0; j < model.dof(); ++j) task_jacobian_column(model, data, p, task_rows(space), j, jac);
}

void task_jacobian_columns(const Model& model, const KinematicsData& data, TaskSpace space, const int* columns,
                           int count, Eigen::Ref<Eigen::MatrixXd> jac) {
  RRLAB_CHECK(jac.rows() == task_rows(space) && jac.cols() == model.dof(),
              jacobian_size_text(jac.rows(), jac.cols(), task_rows(space), model.dof()));
  RRLAB_CHECK(kinematics_data_fits(model, data), kKinematicsDataMisfit);
  const Eigen::Vector3d p = data.end_effector().translation();
  for (int c = 0; c < count; ++c) {
    RRLAB_CHECK(columns[c] >= 0 && columns[c] < model.dof(), index_range_text("column", columns[c], model.dof()));
    task_jacobian_column(model, data, p, task_rows(space), columns[c], jac);
  }
}

JacobianConditioning::JacobianConditioning(int rows, int /*cols*/)
    : jjt_(rows, rows), eig_(rows) {}

void JacobianConditioning::compute(const Eigen::MatrixXd& jac) {
  jjt_.noalias() = jac * jac.transpose();
  eig_.compute(jjt_, Eigen::EigenvaluesOnly);
  const auto& ev = eig_.eigenvalues();  // ascending
  const double lo = std::max(ev[0], 0.0), hi = std::max(ev[ev.size() - 1], 0.0);
  sigma_min_ = std::sqrt(lo);
  sigma_max_ = std::sqrt(hi);
  double det = 1.0;
  for (Eigen::Index i = 0; i < ev.size(); ++i) det *= std::max(ev[i], 0.0);
  manipulability_ = std::sqrt(det);
  condition_ = sigma_min_ > 0 ? sigma_max_ / sigma_min_ : std::numeric_limits<double>::infinity();
}

}  // namespace rrlab

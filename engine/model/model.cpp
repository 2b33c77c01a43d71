#include <rrlab/model/model.hpp>

#include <cmath>

namespace rrlab {

namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();

bool any_finite(const Eigen::VectorXd& v) {
  for (Eigen::Index i = 0; i < v.size(); ++i)
    if (std::isfinite(v[i])) return true;
  return false;
}

Eigen::Isometry3d translation(const Eigen::Vector3d& p) {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.translation() = p;
  return t;
}
}  // namespace

const char* to_string(ModelKind kind) {
  switch (kind) {
    case ModelKind::planar: return "planar";
    case ModelKind::spatial_xz: return "spatial_xz";
    case ModelKind::dh: return "dh";
    case ModelKind::urdf: return "urdf";
  }
  return "?";
}

bool JointLimits::has_position() const { return any_finite(lower) || any_finite(upper); }
bool JointLimits::has_velocity() const { return any_finite(velocity); }
bool JointLimits::has_acceleration() const { return any_finite(acceleration); }

JointLimits unbounded_limits(int dof) {
  JointLimits l;
  l.lower = Eigen::VectorXd::Constant(dof, -kInf);
  l.upper = Eigen::VectorXd::Constant(dof, kInf);
  l.velocity = Eigen::VectorXd::Constant(dof, kInf);
  l.acceleration = Eigen::VectorXd::Constant(dof, kInf);
  return l;
}

namespace {
// kIdentity, k when m turns about e_k (m e_k = e_k, e_kᵀ m = e_kᵀ), else kAnyRotation
int rotation_kind(const Eigen::Matrix3d& m) {
  if (m == Eigen::Matrix3d::Identity()) return JointPlan::kIdentity;
  for (int k = 0; k < 3; ++k) {
    const int i = (k + 1) % 3, j = (k + 2) % 3;
    if (m(k, k) == 1.0 && m(i, k) == 0.0 && m(j, k) == 0.0 && m(k, i) == 0.0 && m(k, j) == 0.0) return k;
  }
  return JointPlan::kAnyRotation;
}
}  // namespace

JointPlan JointPlan::of(const Joint& joint) {
  JointPlan plan;
  plan.pre_rotation = rotation_kind(joint.pre.linear());
  plan.post_rotation = rotation_kind(joint.post.linear());
  for (int d = 0; d < 3; ++d)
    if (joint.axis[d] == 1.0 && joint.axis[(d + 1) % 3] == 0.0 && joint.axis[(d + 2) % 3] == 0.0) plan.axis = d;
  plan.pre_translation = !joint.pre.translation().isZero(0);
  return plan;
}

void Model::plan_joints() {
  joint_plans.clear();
  for (const Joint& joint : joints) joint_plans.push_back(JointPlan::of(joint));
}

double Model::reach() const {
  double r = 0;
  for (const Joint& j : joints) r += j.pre.translation().norm() + j.post.translation().norm();
  return r;
}

Model make_planar(const std::vector<PlanarLinkSpec>& links, const Eigen::Vector2d& base) {
  Model m;
  m.kind = ModelKind::planar;
  m.base = translation({base.x(), base.y(), 0.0});
  for (const auto& l : links) {
    Joint j;  // revolute about z, then along the link's +x
    j.post = translation({l.length, 0, 0});
    m.joints.push_back(j);
    m.links.push_back({m.dof() - 1, l.radius});
  }
  m.limits = unbounded_limits(m.dof());
  m.plan_joints();
  return m;
}

Model make_spatial_xz(const std::vector<PlanarLinkSpec>& links, const Eigen::Vector3d& base) {
  Model m;
  m.kind = ModelKind::spatial_xz;
  m.base = translation(base);
  for (const auto& l : links) {
    // Chen eq. 12: R(θx, θz) = Rx(θx) · Rz(θz), applied to the link vector L_i.
    // The paper prints Rx with the passive sign ([1 0 0; 0 c s; 0 -s c]),
    // which is a turn of θx about -x: the axis below reproduces it exactly.
    Joint jx;
    jx.axis = -Eigen::Vector3d::UnitX();
    Joint jz;
    jz.axis = Eigen::Vector3d::UnitZ();
    jz.post = translation({l.length, 0, 0});
    m.joints.push_back(jx);
    m.joints.push_back(jz);
    m.links.push_back({m.dof() - 1, l.radius});
  }
  m.limits = unbounded_limits(m.dof());
  m.plan_joints();
  return m;
}

Model make_dh(const std::vector<DhLinkSpec>& links, const Eigen::Isometry3d& base) {
  Model m;
  m.kind = ModelKind::dh;
  m.base = base;
  for (const auto& l : links) {
    Joint j;
    j.type = l.joint;
    j.axis = Eigen::Vector3d::UnitZ();
    Eigen::Isometry3d post = Eigen::Isometry3d::Identity();
    if (l.joint == JointType::revolute) {
      // Rz(q + theta) = Rz(q) Rz(theta): the offset sits after the motion.
      post.rotate(Eigen::AngleAxisd(l.theta, Eigen::Vector3d::UnitZ()));
      post.translate(Eigen::Vector3d(0, 0, l.d));
    } else {
      // Rz(theta) Tz(q + d): the rotation offset goes before the slide.
      j.pre.rotate(Eigen::AngleAxisd(l.theta, Eigen::Vector3d::UnitZ()));
      post.translate(Eigen::Vector3d(0, 0, l.d));
    }
    post.translate(Eigen::Vector3d(l.a, 0, 0));
    post.rotate(Eigen::AngleAxisd(l.alpha, Eigen::Vector3d::UnitX()));
    j.post = post;
    m.joints.push_back(j);
    m.links.push_back({m.dof() - 1, l.radius});
  }
  m.limits = unbounded_limits(m.dof());
  m.plan_joints();
  return m;
}

Model make_chain(const Eigen::Isometry3d& base, const std::vector<ChainJointSpec>& joints,
                 const Eigen::Isometry3d& tip) {
  Model m;
  m.kind = ModelKind::urdf;
  m.base = joints.empty() ? base : base * joints.front().origin;
  for (size_t k = 0; k < joints.size(); ++k) {
    Joint j;
    j.type = joints[k].type;
    j.axis = joints[k].axis.normalized();
    j.post = k + 1 < joints.size() ? joints[k + 1].origin : tip;
    m.joints.push_back(j);
    m.links.push_back({m.dof() - 1, joints[k].radius});
  }
  m.limits = unbounded_limits(m.dof());
  m.plan_joints();
  return m;
}

}  // namespace rrlab

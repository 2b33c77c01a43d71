// Robot models: an immutable description shared by every algorithm.
// Every kind (planar, spatial_xz, dh, urdf) is lowered to one serial chain of
// joints, each a fixed transform, a motion about/along its local z or x axis,
// and links (capsules) between consecutive "link frames".
#pragma once

#include <Eigen/Geometry>
#include <limits>
#include <memory>
#include <string>
#include <vector>

namespace rrlab {

struct TriangleMesh;  // collision/mesh_loader.hpp

enum class ModelKind { planar, spatial_xz, dh, urdf };
enum class JointType { revolute, prismatic };

const char* to_string(ModelKind kind);

// One joint of the lowered chain: frame_j = frame_{j-1} * pre * motion(q_j) * post.
// The motion turns about (or slides along) `axis`, a unit vector of the frame
// after `pre`.
struct Joint {
  JointType type = JointType::revolute;
  Eigen::Isometry3d pre = Eigen::Isometry3d::Identity();
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();
  Eigen::Isometry3d post = Eigen::Isometry3d::Identity();
};

// What forward kinematics can skip in a joint's fixed parts, found once
// (Model::plan_joints): a rotation that is the identity, or about a
// coordinate axis (two columns mixed instead of a 3 x 3 product), a zero
// translation. The same numbers as the full products, whose zeros add nothing.
struct JointPlan {
  static constexpr int kIdentity = -2, kAnyRotation = -1;
  int pre_rotation = kAnyRotation, post_rotation = kAnyRotation;  // kIdentity, k (about e_k) or kAnyRotation
  int axis = -1;                 // k when the axis is e_k, else −1
  bool pre_translation = true;   // false: zero
  static JointPlan of(const Joint& joint);
};

// A link is the segment from the end of the previous link (or the base) to the
// origin of the frame after joint `last_joint`; a capsule of `radius`.
// A URDF link with a collision mesh carries it (vertices in the frame after
// `last_joint`); distances are then the mesh's, and `radius` bounds the mesh
// around the segment.
struct Link {
  int last_joint = 0;
  double radius = 0.0;
  std::shared_ptr<const TriangleMesh> mesh;
};

// Two links (0-based, a < b) whose contact is a self-collision.
struct SelfPair {
  int a = 0, b = 0;
  bool operator==(const SelfPair& o) const { return a == o.a && b == o.b; }
};

struct JointLimits {
  Eigen::VectorXd lower, upper;         // position; -inf/+inf when unbounded
  Eigen::VectorXd velocity, acceleration;  // magnitudes; +inf when unbounded
  bool has_position() const;
  bool has_velocity() const;
  bool has_acceleration() const;
};

struct Model {
  ModelKind kind = ModelKind::planar;
  Eigen::Isometry3d base = Eigen::Isometry3d::Identity();
  std::vector<Joint> joints;
  std::vector<Link> links;
  JointLimits limits;
  // The link pairs checked for self-collision: every pair the allowed-collision
  // matrix keeps (collision/allowed_collisions.hpp). Empty: nothing checked.
  std::vector<SelfPair> self_pairs;

  // one per joint, set by the builders (plan_joints); when its size is not
  // dof() (a model assembled by hand) kinematics classifies each joint as it goes
  std::vector<JointPlan> joint_plans;

  int dof() const { return static_cast<int>(joints.size()); }
  void plan_joints();
  int link_count() const { return static_cast<int>(links.size()); }
  // Upper bound of the reach from the base, for scaling and sanity checks.
  double reach() const;
};

// Inputs of the three model builders (already in SI units and radians).
struct PlanarLinkSpec { double length = 1.0, radius = 0.0; };
struct DhLinkSpec {
  double a = 0, alpha = 0, d = 0, theta = 0, radius = 0;
  JointType joint = JointType::revolute;
};

Model make_planar(const std::vector<PlanarLinkSpec>& links, const Eigen::Vector2d& base);
// Chen eq. 11-12: each link is posed by a joint about x then one about z; the
// link vector lies along the local +x axis at zero angles.
Model make_spatial_xz(const std::vector<PlanarLinkSpec>& links, const Eigen::Vector3d& base);
// Standard (distal) DH: T_i = Rz(q_i + theta) Tz(d) Tx(a) Rx(alpha), or for a
// prismatic joint Rz(theta) Tz(q_i + d) Tx(a) Rx(alpha).
Model make_dh(const std::vector<DhLinkSpec>& links, const Eigen::Isometry3d& base);

// One moving joint of a general serial chain (a URDF's revolute, continuous or
// prismatic joint, fixed joints already folded in): `origin` places the joint
// frame in the frame of the previous joint's child link (for the first joint:
// in the chain's base frame), `axis` is a unit vector of the joint frame.
struct ChainJointSpec {
  JointType type = JointType::revolute;
  Eigen::Isometry3d origin = Eigen::Isometry3d::Identity();
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();
  double radius = 0;  // capsule from this joint's origin to the next joint's (or the tip)
};

// A general serial chain (kind urdf). The first joint's origin goes into the
// base (the pedestal up to it does not move and is not a link); joint k carries
// the next joint's origin (or `tip`) as its post transform, so the frame after
// joint k sits on joint k+1's axis and link k is the segment between the two
// joint origins, moved by joints 0..k. The last frame is the tip link's frame.
Model make_chain(const Eigen::Isometry3d& base, const std::vector<ChainJointSpec>& joints,
                 const Eigen::Isometry3d& tip);

// Unbounded limits of the right size; builders call it.
JointLimits unbounded_limits(int dof);

}  // namespace rrlab

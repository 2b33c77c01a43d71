// A serial chain read from a URDF document (parsed with Debian's urdfdom):
// the joints from `base_link` to `tip_link`, fixed joints folded into the
// next moving joint's origin, with the file's position and velocity limits.
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

#include <rrlab/model/model.hpp>

namespace rrlab {

// A URDF that cannot be used; the message names the joint or link at fault.
// `key`: the scenario key at fault when it is not the URDF itself
// ("base_link" or "tip_link" naming a link the URDF lacks), else empty.
class UrdfError : public std::runtime_error {
 public:
  explicit UrdfError(const std::string& message, std::string key = {})
      : std::runtime_error(message), key_(std::move(key)) {}
  const std::string& key() const { return key_; }

 private:
  std::string key_;
};

// A <collision><mesh>: its file as written in the URDF, its scale, and its
// pose in the frame of the moving joint's child link.
struct UrdfMesh {
  std::string link, filename;
  Eigen::Vector3d scale = Eigen::Vector3d::Ones();
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
};

struct UrdfChain {
  std::string base_link, tip_link;
  std::vector<std::string> joint_names;  // the moving joints, base to tip
  std::vector<ChainJointSpec> joints;    // radius: from the <collision> primitives, or -1 when none
  Eigen::Isometry3d tip = Eigen::Isometry3d::Identity();  // tip link in the last joint's child frame
  JointLimits limits;                                      // acceleration unbounded (URDF has none)
  // Collision meshes of each moving joint's link (and of the links fixed to
  // it on the chain), by joint index.
  std::vector<std::vector<UrdfMesh>> meshes;
};

// Bounds on a URDF's size (real arms have tens of links; a humanoid ~100):
// beyond them a document is refused before urdfdom parses it.
inline constexpr std::size_t kMaxUrdfLinks = 1000;
inline constexpr std::size_t kMaxUrdfJoints = 1000;

// `base_link` empty: the URDF's root link; `tip_link` empty: the one leaf of
// the tree (an error when there are several). Throws UrdfError.
UrdfChain read_urdf_chain(const std::string& xml, const std::string& base_link, const std::string& tip_link);

}  // namespace rrlab

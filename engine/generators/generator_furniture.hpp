// Furniture of the URDF families in scenario syntax: boards and blocks
// (boxes turned about z) and upright cylinders (12-sided prisms), placed in a
// frame that stands on the base's floor plane, turned about z.
#pragma once

#include <Eigen/Core>
#include <nlohmann/json.hpp>
#include <string>

namespace rrlab {

// x forward (away from the base), y to the left, z up; `origin` in the world.
struct FloorFrame {
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();
  double yaw = 0;  // rad about z
  Eigen::Vector3d world(const Eigen::Vector3d& local) const;
  Eigen::Vector3d local(const Eigen::Vector3d& world) const;
};

// A box of full edge lengths `size` centred on `center` (frame coordinates),
// its edges along the frame's axes (turned by `yaw` more about z).
nlohmann::json frame_box(const std::string& id, const FloorFrame& frame, const Eigen::Vector3d& center,
                         const Eigen::Vector3d& size, double yaw = 0);
// An upright cylinder (a regular 12-gon prism) of `radius` on the frame's
// point `base` (its bottom), `height` tall.
nlohmann::json frame_cylinder(const std::string& id, const FloorFrame& frame, const Eigen::Vector3d& base,
                              double radius, double height);

}  // namespace rrlab

// Obstacles of a scenario (plain data; FCL stays inside fcl_pairs.cpp and mesh_distance.cpp).
#pragma once

#include <Eigen/Geometry>
#include <memory>
#include <string>
#include <vector>

namespace rrlab {

enum class ShapeKind { polygon, box, sphere, point, wall, mesh };
struct TriangleMesh;  // collision/mesh_loader.hpp
const char* to_string(ShapeKind kind);

// Geometry is given in the obstacle's own frame, placed at `position` (world)
// with `rotation`; a moving obstacle's position is position0 + velocity * t.
struct Obstacle {
  std::string id;
  ShapeKind shape = ShapeKind::point;
  // polygon: vertices in the x-y plane, extruded over z in [z_min, z_max]
  std::vector<Eigen::Vector2d> points;
  double z_min = -1.0, z_max = 1.0;
  Eigen::Vector3d size = Eigen::Vector3d::Zero();  // box: full edge lengths
  double radius = 0.0;                              // sphere
  Eigen::Vector3d normal = Eigen::Vector3d::UnitY();  // wall: outward normal (free side)
  // mesh: triangles in the obstacle's frame (already scaled), shared by copies
  // (live edits move the obstacle, never its triangles); `file` and `scale` as
  // the scenario gave them
  std::shared_ptr<const TriangleMesh> mesh;
  std::string file;
  Eigen::Vector3d scale = Eigen::Vector3d::Ones();
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
  Eigen::Vector3d position0 = Eigen::Vector3d::Zero();  // position at t = 0
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero();
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  // current

  bool moving() const { return !velocity.isZero(0.0); }
};

struct Scene {
  std::vector<Obstacle> obstacles;
  int find(const std::string& id) const;  // -1 when absent
  // Move every obstacle to its pose at time t (constant velocity).
  void advance_to(double t);
};

}  // namespace rrlab

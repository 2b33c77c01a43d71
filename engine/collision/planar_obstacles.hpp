// Obstacles as a planar arm (links in the plane z = 0) meets them, for
// the multi_preview GA's obstacle potential: upright prisms (polygons and
// boxes rotated about z only, across z = 0) as convex polygons, spheres and
// points as circles. The signed segment distances are the collision world's
// (collision/convex_polytope.cpp) restricted to that plane — separated, the
// exact 2D distance; overlapping, the separating-axis depth over the
// polygon's sides, the segment's normal and the prism's caps — at a fraction
// of the cost of the 3D routine, and without witness points, which the
// potential does not need. Any other obstacle (a wall, a mesh, a tilted
// prism, a prism that z = 0 does not cross) leaves the caller on the
// collision world.
#pragma once

#include <Eigen/Core>
#include <limits>
#include <vector>

#include <rrlab/collision/scene.hpp>

namespace rrlab {

class PlanarObstacles {
 public:
  // Geometry of the scene's obstacles (allocates). False when some obstacle
  // is not of the kinds above.
  bool build(const Scene& scene);
  // Poses `ahead` seconds after the scene's current ones (constant velocity;
  // no allocation). False when some prism no longer crosses z = 0 or tilted.
  bool place(const Scene& scene, double ahead);

  // Σ over links and obstacles of max(0, 1 − d/w)², d the signed distance of
  // link l's capsule (joints[l] to joints[l + 1], radius radii[l]) to the
  // obstacle: the sum in Zhang's AMSIP potential U = −h Σ (obstacle_potential).
  double band_sum(const std::vector<Eigen::Vector2d>& joints, const std::vector<double>& radii, double width) const;

  // Signed distance of the segment a-b (in z = 0, no radius) to obstacle k;
  // exact where it is below `cutoff`, else some value at least the cutoff (∞
  // when no part of a prism comes within it).
  double segment_distance(int k, const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                          double cutoff = std::numeric_limits<double>::infinity()) const;

 private:
  struct Part {  // a convex polygon, counter-clockwise
    std::vector<Eigen::Vector2d> local, vertices, normals;  // own frame; world vertices and outward side normals
    std::vector<double> offsets;                             // n · x ≤ offset inside
  };
  struct Shape {
    bool round = false;            // sphere or point: a ball of `radius` at `centre`
    double radius = 0;
    Eigen::Vector3d centre = Eigen::Vector3d::Zero();
    std::vector<Part> parts;       // prism
    double z_min = 0, z_max = 0;   // prism, own frame
    double cap_depth = 0;          // prism: depth of z = 0 below its nearer cap
  };
  static double part_bound(const Part& part, const Eigen::Vector2d& a, const Eigen::Vector2d& b);
  double part_distance(const Shape& shape, const Part& part, const Eigen::Vector2d& a, const Eigen::Vector2d& b) const;

  std::vector<Shape> shapes_;
};

}  // namespace rrlab

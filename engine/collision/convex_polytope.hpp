// Convex primitives in an obstacle's own frame and the exact signed distance
// of a segment (a capsule's axis, no radius) to each: convex polytopes (the
// box, the convex parts of a polygon prism) by separating axes, spheres and
// half-spaces (walls) in closed form.
#pragma once

#include <Eigen/Core>
#include <vector>

#include <rrlab/collision/link_obstacle_distance.hpp>
#include <rrlab/collision/polygon.hpp>

namespace rrlab::collision {

struct Face {
  Eigen::Vector3d normal;  // outward, unit; inside is normal·x <= offset
  double offset = 0;
};

struct Edge {
  int from = 0, to = 0;
  Eigen::Vector3d direction;  // unit
};

struct ConvexPolytope {
  std::vector<Eigen::Vector3d> vertices;
  std::vector<Face> faces;
  std::vector<Edge> edges;
  std::vector<Eigen::Vector3d> edge_axes;  // distinct edge directions up to sign
};

// A counter-clockwise convex polygon extruded over z in [z_min, z_max]:
// k bottom vertices, then the k top ones (fcl_pairs.cpp relies on that order).
ConvexPolytope make_prism(const Polygon2& ccw, double z_min, double z_max);
// A box of full edge lengths `size` centred on the origin (a prism of a rectangle).
ConvexPolytope make_box(const Eigen::Vector3d& size);

// Signed distance of the segment a-b (no radius) to a convex polytope, in the
// polytope's frame: exact when apart, the minimum translation (separating
// axes) when they intersect.
void segment_polytope(const ConvexPolytope& poly, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                      LinkObstacleDistance& out);

// A lower bound of segment_polytope's signed distance, from the face planes
// alone: max over faces of min(n·a, n·b) − offset. The polytope lies behind
// every face plane, so the segment is at least that far from it (and, when
// they intersect, pushing it out along that face's normal takes no less).
double separating_face_bound(const ConvexPolytope& poly, const Eigen::Vector3d& a, const Eigen::Vector3d& b);

// Signed distance of segment a-b to a sphere (a point for radius 0).
void segment_sphere(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& centre, double radius,
                    LinkObstacleDistance& out);

// Half-space behind the plane through `point` with outward unit `normal`.
void segment_wall(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& point,
                  const Eigen::Vector3d& normal, LinkObstacleDistance& out);

}  // namespace rrlab::collision

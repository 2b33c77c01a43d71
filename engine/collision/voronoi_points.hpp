// Obstacle control points for Sezgin et al. (1997) criteria, from the scene
// geometry alone (no FCL): the obstacle vertex nearest to a point (DI, eq. 10)
// and control points on the Voronoi boundary between obstacles (DM, eq. 11).
//
// Candidate points of each obstacle ("vertices"), in world coordinates at the
// obstacle's pose at time t_scene + time_offset (moving obstacles move with
// their constant velocity):
//  - polygon: its vertices (the extruded prism's vertical edge, at the height
//    of the query point clamped into [z_min, z_max]; z = 0 for planar arms);
//    with edge_midpoints also the middle of every edge (Sezgin Ex4 uses the
//    end and middle points of a wall);
//  - box: its 8 corners; point: its position;
//  - sphere: its centre with its radius (the surface point toward the query);
//  - wall (half-space): the foot of the perpendicular from the query point.
//
// Voronoi-boundary control points (Sezgin §3.2 and Ex2, Ex3): for every pair
// of non-wall obstacles, the smallest vertex-to-vertex gap g (sphere radii
// subtracted) is found, and the midpoint of every vertex pair whose gap is
// within `tie` of g becomes a control point (Ex2: the one smallest gap; Ex3's
// two rectangles have two equal gaps, giving (1.4, 1.0) and (1.6, 1.0) as in
// the paper). For every wall and non-wall obstacle, the obstacle's vertex
// nearest to the wall plane gives the midpoint between it and its foot on the
// wall (the gap to a wall), ties likewise. Wall–wall pairs give nothing.
// Cost: O(V²) per obstacle pair, recomputed every step, so the points move
// with moving obstacles.
#pragma once

#include <Eigen/Core>
#include <vector>

#include <rrlab/collision/scene.hpp>

namespace rrlab {

struct ControlPoint {
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  double radius = 0;  // spheres: the surface lies `radius` from `point`
};

// Appends the candidate points of a non-wall obstacle (see above) at height z.
void obstacle_vertices(const Obstacle& o, double z, double time_offset, bool edge_midpoints,
                       std::vector<ControlPoint>& out);

struct NearestObstaclePoint {
  bool found = false;
  int obstacle = -1;
  int candidate = -1;  // index in obstacle_vertices' output for that obstacle (walls: 0)
  double distance = 0;
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
};

// The candidate point of any obstacle nearest to p (Sezgin eq. 10's x_i).
// `scratch` keeps its capacity between calls (no allocation in steady state).
NearestObstaclePoint nearest_obstacle_point(const Scene& scene, const Eigen::Vector3d& p,
                                            double time_offset, bool edge_midpoints,
                                            std::vector<ControlPoint>& scratch);

// Candidate `candidate` of obstacle `obstacle` as seen from p (spheres: the
// surface point toward p; walls: the foot of the perpendicular), so that a
// caller can keep following one vertex (Sezgin eq. 10 with hysteresis on the
// choice of x_i). found = false when the indices no longer name a candidate.
NearestObstaclePoint obstacle_candidate(const Scene& scene, int obstacle, int candidate, const Eigen::Vector3d& p,
                                        double time_offset, bool edge_midpoints,
                                        std::vector<ControlPoint>& scratch);

// Voronoi-boundary control points (see above), appended to `out` after clearing it.
void voronoi_control_points(const Scene& scene, double time_offset, std::vector<ControlPoint>& scratch_a,
                            std::vector<ControlPoint>& scratch_b, std::vector<Eigen::Vector3d>& out,
                            double tie = 1e-9);

}  // namespace rrlab

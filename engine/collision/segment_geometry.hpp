// Exact closest points of segments, points and triangles: the small geometry
// every pair family builds on (no FCL, no allocation), and the tolerances the
// pair routines share.
#pragma once

#include <Eigen/Core>
#include <limits>

namespace rrlab::collision {

inline constexpr double kInfinity = std::numeric_limits<double>::infinity();
// Below this separation (m) a normal from the nearest points is noise: the
// separating-axis normal, defined at contact, is used instead.
inline constexpr double kTouching = 1e-12;
// Slack (m) for "this point lies on that face" tests.
inline constexpr double kOnFace = 1e-12;
// Relative tolerance for parallel directions.
inline constexpr double kParallel = 1e-12;

// Closest points c1 on p1-q1 and c2 on p2-q2 (Ericson, 5.1.9), robust to
// zero-length segments.
void closest_points_segments(const Eigen::Vector3d& p1, const Eigen::Vector3d& q1, const Eigen::Vector3d& p2,
                             const Eigen::Vector3d& q2, Eigen::Vector3d& c1, Eigen::Vector3d& c2);

// The point of segment a-b nearest p (a for a zero-length segment).
Eigen::Vector3d closest_point_on_segment(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& p);

// A unit direction across d, for contacts on a segment's axis where "away" is
// ambiguous; in the x–y plane when possible so planar arms stay planar.
Eigen::Vector3d any_perpendicular(const Eigen::Vector3d& d);

// The point of triangle abc nearest p (Ericson, 5.1.5).
Eigen::Vector3d closest_on_triangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                    const Eigen::Vector3d& c);

}  // namespace rrlab::collision

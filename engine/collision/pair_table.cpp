// The link–obstacle dispatch table: which routine serves each pair.
//
// Capsule links (every link without a collision mesh: its axis segment plus
// a radius): each pair is first solved for the bare segment, then the radius
// is subtracted, which is exact for capsules, including penetration depths.
//
//   capsule x point, sphere  analytic: closest point of a segment to a point
//                            (convex_polytope.cpp, segment_sphere).
//   capsule x wall           analytic: a half-space's signed distance is linear,
//                            so the segment's minimum is at an end point
//                            (segment_wall).
//   capsule x box, polygon   analytic convex-polytope routine (segment_polytope):
//                            separated: exact minimum over the finite features
//                            (end point x face, segment x edge); intersecting:
//                            separating-axis penetration depth over face normals
//                            and segment x edge directions, which is exactly the
//                            minimum translation (see best_separating_axis). A
//                            polygon is the minimum over its convex parts: exact
//                            when apart; when penetrating, the deepest part's
//                            depth, which near an internal diagonal can be less
//                            than the whole polygon's and point across it.
//   capsule x mesh           the segment against the obstacle's OBBRSS tree (FCL's
//                            BVHModel, built once per mesh): RSS bounds prune,
//                            leaves are exact segment–triangle distances
//                            (mesh_distance.cpp, segment_mesh). Exact when apart
//                            and while only the capsule's radius overlaps the
//                            mesh; a segment crossing the surface reports
//                            -kMeshContact (minus the radius); one wholly inside
//                            a closed mesh, minus its distance to the surface
//                            (ray parity decides inside).
//
// Why not FCL for capsules: FCL 0.7 (Debian 0.7.0) failed here in four ways,
// all reproduced while writing this code:
//   - a capsule of radius ~0 (a bare segment) against a box: GJK stops early
//     and returns distances up to 30% too large;
//   - signed distance (EPA via libccd) aborts the process on an assertion in
//     ComputeVisiblePatch for some penetrating capsule-box poses, and throws
//     near touching contact elsewhere (issues #319, #493; Drake #21673);
//   - capsule vs Halfspace distance dereferences a missing GJK support
//     function and crashes;
//   - nearest points are ~1e-7 accurate and lie on the capsule surface, and
//     distances carry GJK's tolerance (issues #127, #275).
// The analytic routines are exact up to rounding and allocate nothing. FCL
// stays the independent reference: the FCL backend (compute_with_fcl) fills
// the same table from fcl::distance / fcl::collide (Capsule vs Convex, Box,
// Sphere, BVH; walls analytic there too, fcl_pairs.cpp), and the tests check
// that both agree on random poses.
//
// A zero link radius needs no special case: the segment routines are exact.
//
// Links with a collision mesh (URDF robots) are the exception, and the same
// in both backends: against boxes, polygon prisms and meshes their distances
// come from FCL's BVH model (OBBRSS) of the mesh against the obstacle's FCL
// shape (a mesh obstacle: BVH–BVH distance, exact triangle pairs); spheres
// and points by the nearest triangle (FCL 0.7.0's mesh–sphere distance
// reported contact at every pose here, with either GJK solver); walls
// analytic (the lowest vertex). FCL's mesh distance gives no penetration
// depth: a penetrating mesh link reports -kMeshContact.
#include <rrlab/collision/pair_table.hpp>

#include <rrlab/collision/fcl_pairs.hpp>

namespace rrlab::collision {

namespace {

using SegmentDistance = void (*)(const ObstacleGeometry& g, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                 LinkObstacleDistance& out);

// A capsule: the bare segment's distance, then the radius.
template <SegmentDistance segment_distance>
void capsule_pair(const PairLink& link, const PairObstacle& obstacle, LinkObstacleDistance& out) {
  segment_distance(*obstacle.geometry, link.start, link.end, out);
  out.distance -= link.radius;  // capsule = segment grown by its radius
}

// A capsule by FCL's queries (the FCL capsule carries the radius).
void capsule_by_fcl(const PairLink& link, const PairObstacle& obstacle, LinkObstacleDistance& out) {
  fcl_capsule_obstacle(*link.fcl, *obstacle.geometry, *obstacle.fcl, out);
}

void mesh_link_wall(const PairLink& link, const PairObstacle& obstacle, LinkObstacleDistance& out) {
  const ObstacleGeometry& g = *obstacle.geometry;
  mesh_wall(*link.mesh, *link.pose, g.position, g.rotation * g.normal, out);
}

void mesh_link_sphere(const PairLink& link, const PairObstacle& obstacle, LinkObstacleDistance& out) {
  mesh_sphere(*link.mesh, *link.pose, obstacle.geometry->position, obstacle.geometry->radius, out);
}

void mesh_link_point(const PairLink& link, const PairObstacle& obstacle, LinkObstacleDistance& out) {
  mesh_sphere(*link.mesh, *link.pose, obstacle.geometry->position, 0.0, out);
}

void mesh_link_by_fcl(const PairLink& link, const PairObstacle& obstacle, LinkObstacleDistance& out) {
  fcl_mesh_obstacle(*link.bvh, *link.pose, *obstacle.geometry, *obstacle.fcl, out);
}

constexpr PairFunction kCapsulePolytopes = capsule_pair<segment_polytopes>;
constexpr PairFunction kCapsuleSphere = capsule_pair<segment_sphere_obstacle>;
constexpr PairFunction kCapsulePoint = capsule_pair<segment_point>;
constexpr PairFunction kCapsuleWall = capsule_pair<segment_wall_obstacle>;
constexpr PairFunction kCapsuleMesh = capsule_pair<segment_mesh_obstacle>;

}  // namespace

// [backend][link shape][obstacle shape], the columns in ShapeKind's order:
// polygon, box, sphere, point, wall, mesh.
const PairFunction kPairTable[kBackends][kLinkShapes][kObstacleShapes] = {
    {
        // DistanceBackend::analytic, capsule links
        {kCapsulePolytopes, kCapsulePolytopes, kCapsuleSphere, kCapsulePoint, kCapsuleWall, kCapsuleMesh},
        // DistanceBackend::analytic, mesh links
        {mesh_link_by_fcl, mesh_link_by_fcl, mesh_link_sphere, mesh_link_point, mesh_link_wall, mesh_link_by_fcl},
    },
    {
        // DistanceBackend::fcl, capsule links: FCL's queries but against walls
        {capsule_by_fcl, capsule_by_fcl, capsule_by_fcl, capsule_by_fcl, kCapsuleWall, capsule_by_fcl},
        // DistanceBackend::fcl, mesh links: as in the analytic backend
        {mesh_link_by_fcl, mesh_link_by_fcl, mesh_link_sphere, mesh_link_point, mesh_link_wall, mesh_link_by_fcl},
    },
};

}  // namespace rrlab::collision

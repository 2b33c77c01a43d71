// The FCL adapters, and with mesh_distance.cpp the only file that includes
// FCL. compute() uses FCL only for mesh links against boxes, polygon prisms
// and meshes; the reference backend (compute_with_fcl) fills the whole table
// from fcl::distance / fcl::collide, and the tests check that both agree on
// random poses. Why compute() does not use FCL for capsules: pair_table.cpp.
#include <rrlab/collision/fcl_pairs.hpp>

#include <fcl/fcl.h>

#include <algorithm>
#include <utility>
#include <vector>

#include <rrlab/collision/segment_geometry.hpp>

namespace rrlab::collision {

using Eigen::Vector3d;

struct FclObstacle {
  std::vector<std::shared_ptr<fcl::CollisionGeometryd>> parts;
};

struct FclCapsule {
  explicit FclCapsule(double radius) : capsule(radius, 0.0) {}
  fcl::Capsuled capsule;
  fcl::Transform3d pose = fcl::Transform3d::Identity();
  Vector3d start = Vector3d::Zero(), end = Vector3d::Zero();  // axis segment
  double inflation = 0;  // added to the radius for FCL's sake
};

namespace {

std::shared_ptr<fcl::Convexd> make_fcl_prism(const ConvexPolytope& prism) {
  // make_prism's layout: k bottom vertices, then k top ones
  const int k = static_cast<int>(prism.vertices.size()) / 2;
  auto vertices = std::make_shared<std::vector<Vector3d>>(prism.vertices);
  auto faces = std::make_shared<std::vector<int>>();
  faces->push_back(k);  // bottom, seen from below: clockwise in x–y
  for (int i = k - 1; i >= 0; --i) faces->push_back(i);
  faces->push_back(k);  // top
  for (int i = 0; i < k; ++i) faces->push_back(k + i);
  for (int i = 0; i < k; ++i) {
    const int j = (i + 1) % k;
    faces->insert(faces->end(), {4, i, j, k + j, k + i});
  }
  return std::make_shared<fcl::Convexd>(vertices, k + 2, faces);
}

// Smallest capsule radius FCL's GJK handles (see pose_fcl_capsule).
constexpr double kFclMinRadius = 1e-3;

fcl::Transform3d capsule_pose(const Vector3d& a, const Vector3d& b) {
  fcl::Transform3d pose = fcl::Transform3d::Identity();
  pose.translation() = 0.5 * (a + b);
  if ((b - a).norm() > 0)
    pose.linear() = Eigen::Quaterniond::FromTwoVectors(Vector3d::UnitZ(), b - a).toRotationMatrix();
  return pose;
}

// FCL's points lie on the capsule surface: step back to the axis.
void from_fcl_points(const FclCapsule& link, double distance, const Vector3d& on_capsule,
                     const Vector3d& on_obstacle, LinkObstacleDistance& out) {
  out.distance = distance + link.inflation;
  out.on_link = closest_point_on_segment(link.start, link.end, on_capsule);
  out.on_obstacle = on_obstacle;
  const Vector3d gap = on_capsule - on_obstacle;
  out.normal = gap.norm() > 0 ? Vector3d(gap.normalized()) : Vector3d::Zero();
}

// One capsule against one FCL shape: GJK distance when apart, else the depth
// from fcl::collide's contact (libccd MPR). FCL's signed distance (EPA) is not
// used: in 0.7 it aborts on an assertion in ComputeVisiblePatch for some
// penetrating poses, which no try/catch survives.
void fcl_pair(const FclCapsule& link, const fcl::CollisionGeometryd& shape,
              const fcl::Transform3d& shape_pose, LinkObstacleDistance& out) {
  fcl::DistanceRequestd distance_request(true, false, 0.0, 0.0, 1e-10, fcl::GST_LIBCCD);
  fcl::DistanceResultd distance_result;
  fcl::distance(&link.capsule, link.pose, &shape, shape_pose, distance_request, distance_result);
  // a shape against a BVH (a mesh obstacle) is solved as BVH against shape,
  // and FCL 0.7 hands back the nearest points in that order
  if (shape.getObjectType() == fcl::OT_BVH)
    std::swap(distance_result.nearest_points[0], distance_result.nearest_points[1]);
  if (distance_result.min_distance > 0) {
    from_fcl_points(link, distance_result.min_distance, distance_result.nearest_points[0],
                    distance_result.nearest_points[1], out);
    return;
  }
  fcl::CollisionRequestd collision_request(1, true);
  fcl::CollisionResultd collision_result;
  fcl::collide(&link.capsule, link.pose, &shape, shape_pose, collision_request, collision_result);
  if (collision_result.numContacts() == 0) {  // touching: GJK says 0, MPR says apart
    from_fcl_points(link, 0.0, distance_result.nearest_points[0],
                    distance_result.nearest_points[1], out);
    return;
  }
  const fcl::Contactd& contact = collision_result.getContact(0);
  out.distance = -contact.penetration_depth + link.inflation;
  out.normal = -contact.normal;  // FCL's points from the link into the obstacle
  out.on_link = closest_point_on_segment(link.start, link.end, contact.pos);
  out.on_obstacle = contact.pos;
}

}  // namespace

std::shared_ptr<FclObstacle> build_fcl(const Obstacle& o, const ObstacleGeometry& g) {
  auto built = std::make_shared<FclObstacle>();
  FclObstacle& f = *built;
  switch (o.shape) {
    case ShapeKind::polygon:
      for (const ConvexPolytope& part : g.parts) f.parts.push_back(make_fcl_prism(part));
      break;
    case ShapeKind::box: f.parts.push_back(std::make_shared<fcl::Boxd>(o.size)); break;
    case ShapeKind::sphere: f.parts.push_back(std::make_shared<fcl::Sphered>(g.radius)); break;
    case ShapeKind::point: f.parts.push_back(std::make_shared<fcl::Sphered>(0.0)); break;
    case ShapeKind::wall:
      // none: FCL 0.7 has no distance query for a Halfspace; its generic GJK
      // then calls a missing support function and crashes
      break;
    case ShapeKind::mesh: f.parts.push_back(g.bvh); break;  // BVH: against capsules and mesh links
  }
  return built;
}

std::shared_ptr<FclCapsule> make_fcl_capsule(double radius) { return std::make_shared<FclCapsule>(radius); }

void pose_fcl_capsule(FclCapsule& link, const Vector3d& a, const Vector3d& b, double radius) {
  // FCL's GJK stops early on a segment (radius ~0) against a box and can be
  // 30% off: give such links 1 mm and take it back from the distances
  const double inflation = std::max(0.0, kFclMinRadius - radius);
  fcl::Capsuled& capsule = link.capsule;
  capsule.radius = radius + inflation;
  capsule.lz = (b - a).norm();
  capsule.computeLocalAABB();
  link.pose = capsule_pose(a, b);
  link.start = a;
  link.end = b;
  link.inflation = inflation;
}

void fcl_capsule_obstacle(const FclCapsule& link, const ObstacleGeometry& g, const FclObstacle& shapes,
                          LinkObstacleDistance& pair) {
  fcl::Transform3d obstacle_pose = fcl::Transform3d::Identity();
  obstacle_pose.linear() = g.rotation;
  obstacle_pose.translation() = g.position;
  pair.distance = kInfinity;
  LinkObstacleDistance part_result;
  for (const auto& part : shapes.parts) {
    fcl_pair(link, *part, obstacle_pose, part_result);
    if (part_result.distance < pair.distance) pair = part_result;
  }
}

// One mesh link against a box, a polygon prism or a mesh: FCL's BVH distance
// (a mesh obstacle: BVH–BVH, exact triangle pairs).
void fcl_mesh_obstacle(const MeshBvh& bvh, const Eigen::Isometry3d& link_pose, const ObstacleGeometry& g,
                       const FclObstacle& shapes, LinkObstacleDistance& out) {
  fcl::Transform3d obstacle_pose = fcl::Transform3d::Identity();
  obstacle_pose.linear() = g.rotation;
  obstacle_pose.translation() = g.position;
  out.distance = kInfinity;
  for (const auto& part : shapes.parts) {
    // FCL's own GJK (GST_INDEP): with libccd's, a mesh against a sphere
    // reported contact at every pose here (FCL 0.7.0)
    fcl::DistanceRequestd request(true, false, 0.0, 0.0, 1e-10, fcl::GST_INDEP);
    fcl::DistanceResultd result;
    fcl::distance(&bvh, link_pose, part.get(), obstacle_pose, request, result);
    double d = result.min_distance;
    if (d >= out.distance) continue;
    out.on_link = result.nearest_points[0];
    out.on_obstacle = result.nearest_points[1];
    if (d <= 0) {  // touching or penetrating: no depth, nor points, from FCL's mesh distance
      d = -kMeshContact;
      out.on_link = link_pose.translation();
      out.on_obstacle = g.position;
      const Vector3d away = link_pose.translation() - g.position;
      out.normal = away.norm() > 0 ? Vector3d(away.normalized()) : Vector3d::UnitZ();
    } else {
      out.normal = (out.on_link - out.on_obstacle) / d;
    }
    out.distance = d;
  }
}

double fcl_mesh_mesh(const MeshBvh& a, const Eigen::Isometry3d& pose_a, const MeshBvh& b,
                     const Eigen::Isometry3d& pose_b, Vector3d& on_a, Vector3d& on_b) {
  fcl::DistanceRequestd request(true, false, 0.0, 0.0, 1e-10, fcl::GST_INDEP);
  fcl::DistanceResultd result;
  fcl::distance(&a, pose_a, &b, pose_b, request, result);
  on_a = result.nearest_points[0];
  on_b = result.nearest_points[1];
  if (result.min_distance > 0) return result.min_distance;
  on_a = pose_a.translation();  // no points from FCL's mesh distance at contact
  on_b = pose_b.translation();
  return -kMeshContact;
}

}  // namespace rrlab::collision
